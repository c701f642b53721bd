// Fixed-radius queries of the dense point grid against brute force, also for queries outside the
// points' bounding box, for a grid rebuilt in place and for a sparse set whose cells must grow.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "stocs/geometry/point_grid.h"

namespace stocs {
namespace {

std::vector<Eigen::Vector3f> randomPoints(size_t n, float spread, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-spread, spread);
  std::vector<Eigen::Vector3f> points(n);
  for (Eigen::Vector3f& p : points) p = {u(rng), u(rng), u(rng)};
  return points;
}

std::vector<int> bruteForceWithin(const std::vector<Eigen::Vector3f>& points,
                                  const Eigen::Vector3f& q, float radius) {
  std::vector<int> found;
  for (size_t i = 0; i < points.size(); ++i) {
    if ((points[i] - q).squaredNorm() < radius * radius) found.push_back(static_cast<int>(i));
  }
  return found;
}

void expectSameAsBruteForce(const PointGrid& grid, const std::vector<Eigen::Vector3f>& points,
                            float radius, float query_spread) {
  for (const Eigen::Vector3f& q : randomPoints(300, query_spread, 7)) {
    std::vector<int> found;
    grid.forEachWithin(q, radius, [&](int i, float d2) {
      EXPECT_FLOAT_EQ(d2, (points[i] - q).squaredNorm());
      found.push_back(i);
    });
    std::sort(found.begin(), found.end());
    ASSERT_EQ(found, bruteForceWithin(points, q, radius)) << q.transpose();
  }
}

TEST(PointGrid, FindsExactlyThePointsWithinTheRadius) {
  const auto points = randomPoints(2000, 0.05f, 1);
  const PointGrid grid(points, 0.01f);
  expectSameAsBruteForce(grid, points, 0.01f, 0.06f);   // some queries lie outside the box
  expectSameAsBruteForce(grid, points, 0.025f, 0.06f);  // a radius of several cells
}

TEST(PointGrid, RunsHoldEveryPointUpToTheRadiusOnce) {
  // Base sampling draws among the runs' points: every point at most `radius` away must be there
  // (the PPF map accepts a pair of exactly its longest length), and none twice.
  auto points = randomPoints(2000, 0.05f, 3);
  points.push_back({0.02f, 0, 0});
  points.push_back({0.02f + 0.015f, 0, 0});  // exactly the radius from the query below
  const PointGrid grid(points, 0.015f);
  auto queries = randomPoints(200, 0.06f, 5);
  queries.push_back({0.02f, 0, 0});
  for (const Eigen::Vector3f& q : queries) {
    std::vector<int> seen(points.size(), 0);
    grid.forEachRun(q, 0.015f, [&](uint32_t begin, uint32_t end) {
      ASSERT_LT(begin, end);
      for (uint32_t k = begin; k < end; ++k) ++seen[grid.originalIndex(k)];
    });
    for (size_t i = 0; i < points.size(); ++i) {
      ASSERT_LE(seen[i], 1) << "point " << i << " in two runs";
      if ((points[i] - q).norm() <= 0.015f) {
        ASSERT_EQ(seen[i], 1) << "point " << i << " missed";
      }
    }
  }
}

TEST(PointGrid, ClosestWithinPrefersTheNearestAndThenTheLowerIndex) {
  const std::vector<Eigen::Vector3f> points = {{0, 0, 0}, {0.003f, 0, 0}, {0.003f, 0, 0}};
  const PointGrid grid(points, 0.005f);
  float d2 = -1;
  EXPECT_EQ(grid.closestWithin({0.0025f, 0, 0}, 0.005f, &d2), 1);
  EXPECT_NEAR(d2, 0.0005f * 0.0005f, 1e-12f);
  EXPECT_EQ(grid.closestWithin({0.001f, 0, 0}, 0.005f), 0);
  EXPECT_EQ(grid.closestWithin({0.02f, 0, 0}, 0.005f), -1);
  EXPECT_EQ(grid.closestWithin({1e30f, -1e30f, 0}, 0.005f), -1);  // far outside: no overflow
}

TEST(PointGrid, AssignRebuildsInPlace) {
  PointGrid grid(randomPoints(500, 0.05f, 2), 0.01f);
  const auto points = randomPoints(800, 0.02f, 3);
  grid.assign(points, 0.004f);
  expectSameAsBruteForce(grid, points, 0.004f, 0.03f);
  grid.assign({}, 0.004f);
  EXPECT_TRUE(grid.empty());
  EXPECT_EQ(grid.closestWithin({0, 0, 0}, 1.0f), -1);
}

TEST(PointGrid, ASparseWideSetGetsLargerCellsAndStaysExact) {
  // 50 points over 20 m at 1 mm cells would need 8e15 cells.
  const auto points = randomPoints(50, 10.0f, 4);
  const PointGrid grid(points, 0.001f);
  EXPECT_GT(grid.cellSize(), 0.1f);
  expectSameAsBruteForce(grid, points, 3.0f, 12.0f);
}

TEST(PointGrid, RefusesNonFinitePointsAndCells) {
  EXPECT_THROW(PointGrid({{0, 0, 0}, {NAN, 0, 0}}, 0.01f), std::invalid_argument);
  // In any coordinate and any place, also the first point (which seeds the bounding box).
  EXPECT_THROW(PointGrid({{0, 0, NAN}, {0, 0, 0}}, 0.01f), std::invalid_argument);
  EXPECT_THROW(PointGrid({{0, 0, 0}, {0, 0, 0}, {0, -INFINITY, 0}}, 0.01f), std::invalid_argument);
  EXPECT_THROW(PointGrid({{0, 0, 0}, {0, 0, INFINITY}}, 0.01f), std::invalid_argument);
  EXPECT_THROW(PointGrid({{0, 0, 0}}, 0.0f), std::invalid_argument);
}

}  // namespace
}  // namespace stocs
