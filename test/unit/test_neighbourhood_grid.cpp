// Fixed-radius nearest-point queries, over all points or a subset of them.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "stocs/geometry/neighbourhood_grid.h"

namespace stocs {
namespace {

const std::vector<Eigen::Vector3f> kPoints = {
    {0, 0, 0}, {0.004f, 0, 0}, {0.0045f, 0, 0}, {0.02f, 0, 0}, {-0.003f, 0.003f, 0}};

TEST(NeighbourhoodGrid, ClosestWithinTheRadiusOrNone) {
  const NeighbourhoodGrid grid(kPoints, 0.005f);
  EXPECT_EQ(grid.closest({0.001f, 0, 0}), 0);
  EXPECT_EQ(grid.closest({0.0041f, 0, 0}), 1);
  EXPECT_EQ(grid.closest({0.0199f, 0.001f, 0}), 3);
  EXPECT_EQ(grid.closest({0.012f, 0, 0}), -1);  // 7.5 mm from 0.0045 and 8 mm from 0.02
  EXPECT_EQ(grid.closest({0, 0, 0.005f}), -1);  // exactly at the radius: not strictly within
}

TEST(NeighbourhoodGrid, ASubsetAnswersWithOriginalIndices) {
  const NeighbourhoodGrid subset(kPoints, std::vector<uint32_t>{2, 4}, 0.005f);
  EXPECT_EQ(subset.closest({-0.001f, 0.001f, 0}), 4);  // 0 is closer but not in the subset
  EXPECT_EQ(subset.closest({0.0043f, 0, 0}), 2);
  EXPECT_EQ(subset.closest({0.02f, 0, 0}), -1);
  const NeighbourhoodGrid none(kPoints, std::vector<uint32_t>{}, 0.005f);
  EXPECT_EQ(none.closest({0, 0, 0}), -1);
}

TEST(NeighbourhoodGrid, EveryPointWithinTheRadiusIsVisited) {
  const NeighbourhoodGrid grid(kPoints, 0.005f);
  std::vector<int> seen;
  grid.forEachWithin({0.002f, 0, 0}, [&](int i, float) { seen.push_back(i); });
  std::sort(seen.begin(), seen.end());
  EXPECT_EQ(seen, (std::vector<int>{0, 1, 2}));  // 4 is 5.8 mm away
}

/// Index of the point of `points` closest to `query` strictly within `radius`, or -1.
int bruteForceClosest(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f& query,
                      float radius) {
  int expected = -1;
  float best = radius * radius;
  for (size_t i = 0; i < points.size(); ++i) {
    const float d2 = (points[i] - query).squaredNorm();
    if (d2 < best) {
      best = d2;
      expected = static_cast<int>(i);
    }
  }
  return expected;
}

TEST(NeighbourhoodGrid, MatchesBruteForceOnASurfaceAndFarAway) {
  // Points on a wavy sheet as on a depth surface, queries on and off it (also outside the grid).
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-0.1f, 0.1f);
  std::vector<Eigen::Vector3f> points(3000);
  for (Eigen::Vector3f& p : points) {
    p.x() = u(rng);
    p.y() = u(rng);
    p.z() = 0.01f * std::sin(30 * p.x()) + 0.002f * u(rng);
  }
  const float radius = 0.005f;
  const NeighbourhoodGrid grid(points, radius);
  for (int q = 0; q < 2000; ++q) {
    const Eigen::Vector3f query(1.2f * u(rng), 1.2f * u(rng), 0.15f * u(rng));
    ASSERT_EQ(grid.closest(query), bruteForceClosest(points, query, radius)) << query.transpose();
  }
}

TEST(NeighbourhoodGrid, ASurfaceInAWideScatteredBackgroundKeepsCellsOfTheRadius) {
  // As in a soft segment: an object's surface plus background pixels above the threshold scattered
  // over a 1 m box. The cells stay at the radius (they grew to several times it when one dense
  // index had to cover the whole box), and queries on the surface, the background and between
  // them are exact.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-0.05f, 0.05f), wide(-0.5f, 0.5f);
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i < 4000; ++i) points.emplace_back(u(rng), u(rng), 0.5f + 0.1f * u(rng) * u(rng));
  for (int i = 0; i < 800; ++i) points.emplace_back(wide(rng), wide(rng), 0.8f + 0.6f * wide(rng));
  const float radius = 0.005f;
  const NeighbourhoodGrid grid(points, radius);
  EXPECT_FLOAT_EQ(grid.cellSize(), radius);
  int found = 0;
  for (int q = 0; q < 3000; ++q) {
    const Eigen::Vector3f& near = points[static_cast<size_t>(q) % points.size()];
    const Eigen::Vector3f query =
        q % 3 == 0 ? Eigen::Vector3f(wide(rng), wide(rng), 0.8f + 0.6f * wide(rng))
                   : Eigen::Vector3f(near + 0.1f * Eigen::Vector3f(u(rng), u(rng), u(rng)));
    const int expected = bruteForceClosest(points, query, radius);
    found += expected >= 0;
    ASSERT_EQ(grid.closest(query), expected) << query.transpose();
  }
  EXPECT_GT(found, 1000);  // the queries do test the lists, not only empty space
}

TEST(NeighbourhoodGrid, ASparseWideSetStaysExact) {
  // Two points 100 m apart: half-radius cells over their box would be 1e14 cells.
  const std::vector<Eigen::Vector3f> points = {{0, 0, 0}, {100, 100, 100}};
  const NeighbourhoodGrid grid(points, 0.005f);
  EXPECT_GT(grid.cellSize(), 1.0f);  // the memory bound made the cells grow
  EXPECT_EQ(grid.closest({0.001f, 0.001f, 0.001f}), 0);
  EXPECT_EQ(grid.closest({100, 100, 100.004f}), 1);
  EXPECT_EQ(grid.closest({50, 50, 50}), -1);
  EXPECT_EQ(grid.closest({NAN, 0, 0}), -1);
  EXPECT_THROW(NeighbourhoodGrid({{0, 0, 0}, {0, NAN, 0}}, 0.005f), std::invalid_argument);
}

}  // namespace
}  // namespace stocs
