// The plane an object rests on: found among clutter, facing the camera, and none where no plane
// holds enough of the points.
#include <gtest/gtest.h>

#include <random>

#include "stocs/segmentation/support_plane.h"

namespace stocs {
namespace {

/// A tilted table 0.8 m in front of the camera (`on_table` points, 1 mm of noise) and boxes' worth
/// of points above it (`clutter`).
std::vector<Eigen::Vector3f> tableWithClutter(int on_table, int clutter, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> across(-0.3f, 0.3f);
  std::normal_distribution<float> noise(0.0f, 0.001f);
  std::vector<Eigen::Vector3f> points;
  for (int k = 0; k < on_table; ++k) {
    const float x = across(rng), y = across(rng);
    points.emplace_back(x, y, 0.8f + 0.5f * y + noise(rng));  // z rises with y: tilted
  }
  std::uniform_real_distribution<float> height(0.01f, 0.1f);
  for (int k = 0; k < clutter; ++k) {
    const float x = across(rng), y = across(rng);
    points.emplace_back(x, y, 0.8f + 0.5f * y - height(rng));
  }
  return points;
}

TEST(SupportPlane, FindsTheTableAmongClutterFacingTheCamera) {
  const std::optional<Plane> plane = dominantPlane(tableWithClutter(1200, 800, 1), 0.004f, 500);
  ASSERT_TRUE(plane.has_value());
  const Eigen::Vector3f expected = Eigen::Vector3f(0, 0.5f, -1).normalized();  // towards the origin
  EXPECT_GT(plane->normal.dot(expected), std::cos(1.0 * M_PI / 180));
  EXPECT_NEAR(plane->distance(Eigen::Vector3f(0, 0, 0.8f)), 0.0f, 0.001f);
  EXPECT_GT(plane->distance(Eigen::Vector3f::Zero()), 0.0f);
  EXPECT_NEAR(plane->distance(Eigen::Vector3f(0, 0, 0.75f)),
              0.05f * expected.dot(-Eigen::Vector3f::UnitZ()), 0.001f);
}

TEST(SupportPlane, NoneWhereTooFewPointsLieOnOne) {
  EXPECT_FALSE(dominantPlane(tableWithClutter(300, 1700, 2), 0.004f, 500).has_value());
  EXPECT_FALSE(dominantPlane({}, 0.004f, 0).has_value());
  EXPECT_FALSE(
      dominantPlane({Eigen::Vector3f(0, 0, 1), Eigen::Vector3f(0, 1, 1)}, 0.004f, 0).has_value());
}

}  // namespace
}  // namespace stocs
