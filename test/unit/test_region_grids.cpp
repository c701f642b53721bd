// RegionGrids: each grid answers as a grid built over its points would, whichever thread builds it
// first.
#include "stocs/estimation/stages/region_grids.h"

#include <gtest/gtest.h>

#include <random>
#include <thread>
#include <vector>

namespace stocs {
namespace {

class RegionGridsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> coord(0.0f, 0.05f);
    std::uniform_int_distribution<int> pick(-1, 3);
    for (int i = 0; i < 400; ++i) {
      points_.emplace_back(coord(rng), coord(rng), coord(rng));
      region_.push_back(pick(rng));  // regions -1 (boundary) to 3
      queries_.emplace_back(coord(rng), coord(rng), coord(rng));
    }
  }

  /// The closest point of `region` (-1: any) strictly within the radius, by brute force.
  int bruteForce(const Eigen::Vector3f& q, int region) const {
    int best = -1;
    float best_d2 = kRadius * kRadius;
    for (size_t i = 0; i < points_.size(); ++i) {
      if (region >= 0 && region_[i] != region) continue;
      const float d2 = (points_[i] - q).squaredNorm();
      if (d2 < best_d2) {
        best = static_cast<int>(i);
        best_d2 = d2;
      }
    }
    return best;
  }

  static constexpr float kRadius = 0.006f;
  std::vector<Eigen::Vector3f> points_, queries_;
  std::vector<int> region_;
};

TEST_F(RegionGridsTest, EachRegionsGridHoldsItsPointsAndNegativeMeansAll) {
  const RegionGrids grids(points_, region_, kRadius);
  for (int region : {-1, 0, 1, 2, 3}) {
    for (const Eigen::Vector3f& q : queries_) {
      ASSERT_EQ(grids.of(region).closest(q), bruteForce(q, region)) << region;
    }
  }
  // A region without points has an empty grid.
  EXPECT_EQ(grids.of(7).closest(points_.front()), -1);
  EXPECT_EQ(&grids.of(1), &grids.of(1));  // built once
}

TEST_F(RegionGridsTest, WithoutRegionsEveryQueryTakesAllPoints) {
  const std::vector<int> none;
  const RegionGrids grids(points_, none, kRadius);
  for (const Eigen::Vector3f& q : queries_) {
    ASSERT_EQ(grids.of(2).closest(q), bruteForce(q, -1));
    ASSERT_EQ(grids.of(-1).closest(q), bruteForce(q, -1));
  }
}

TEST_F(RegionGridsTest, ThreadsBuildingAGridAtOnceGetTheSameOne) {
  const RegionGrids grids(points_, region_, kRadius);
  std::vector<std::vector<int>> answers(4);
  std::vector<std::thread> threads;
  for (size_t t = 0; t < answers.size(); ++t) {
    threads.emplace_back([&, t] {
      for (const Eigen::Vector3f& q : queries_) answers[t].push_back(grids.of(1).closest(q));
    });
  }
  for (std::thread& t : threads) t.join();
  for (size_t k = 0; k < queries_.size(); ++k) {
    for (const std::vector<int>& a : answers) ASSERT_EQ(a[k], bruteForce(queries_[k], 1));
  }
}

}  // namespace
}  // namespace stocs
