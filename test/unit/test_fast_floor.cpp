// floorFast / ceilFast against std::floor / std::ceil.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "stocs/util/fast_floor.h"

namespace stocs {
namespace {

TEST(FastFloor, MatchesStdFloorAndCeil) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> small(-100.0f, 100.0f), wide(-1e9f, 1e9f);
  for (int i = 0; i < 200000; ++i) {
    const float x = i % 2 ? small(rng) : wide(rng);
    ASSERT_EQ(floorFast(x), std::floor(x)) << x;
    ASSERT_EQ(ceilFast(x), std::ceil(x)) << x;
  }
  for (float x : {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, -0.5f, 2.999999f, -2.999999f, 8388607.5f,
                  -8388607.5f, 8388608.0f, -8388609.0f, 1e30f, -1e30f, std::nextafter(1.0f, 0.0f),
                  std::nextafter(-1.0f, 0.0f)}) {
    EXPECT_EQ(floorFast(x), std::floor(x)) << x;
    EXPECT_EQ(ceilFast(x), std::ceil(x)) << x;
  }
  EXPECT_TRUE(std::isnan(floorFast(std::numeric_limits<float>::quiet_NaN())));
  EXPECT_EQ(floorFast(std::numeric_limits<float>::infinity()),
            std::numeric_limits<float>::infinity());
  EXPECT_EQ(ceilFast(-std::numeric_limits<float>::infinity()),
            -std::numeric_limits<float>::infinity());
}

}  // namespace
}  // namespace stocs
