// Fixed-radius nearest-point queries, over all points or a subset of them.
#include <gtest/gtest.h>

#include <algorithm>

#include "stocs/neighbourhood_grid.h"

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

}  // namespace
}  // namespace stocs
