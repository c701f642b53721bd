// The free-space check on a hand-made scene: a flat wall 1 m away seen by a small camera, and model
// samples in front of it, on it, behind it, facing away, off the image and over missing pixels.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <opencv2/core.hpp>

#include "stocs/estimation/stages/free_space_check.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

constexpr int kSize = 20;

CameraIntrinsics camera() {
  return {20.0, 20.0, 9.5, 9.5, kSize, kSize};
}

/// Every pixel sees the plane z = 1 m, except column 0, which measured nothing.
OrganizedCloud wall() {
  OrganizedCloud cloud(kSize, kSize);
  const CameraIntrinsics k = camera();
  for (int v = 0; v < kSize; ++v) {
    for (int u = 0; u < kSize; ++u) {
      const float x = static_cast<float>((u - k.cx) / k.fx),
                  y = static_cast<float>((v - k.cy) / k.fy);
      cloud.points[v * kSize + u] =
          u == 0 ? Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN())
                 : Eigen::Vector3f(x, y, 1);
    }
  }
  return cloud;
}

/// Samples at (x, 0, z) with normals towards the camera unless `away`.
ObjectModel samples(const std::vector<std::pair<float, float>>& xz, bool away = false) {
  ObjectModel m;
  for (const auto& [x, z] : xz) {
    m.points.emplace_back(x, 0, z);
    m.normals.emplace_back(0, 0, away ? 1 : -1);
  }
  return m;
}

TEST(FreeSpaceCheck, CountsCameraFacingSamplesInFrontOfTheMeasuredSurface) {
  const OrganizedCloud cloud = wall();
  const CameraIntrinsics k = camera();
  const FreeSpaceCheck check(cloud, k, FreeSpaceParams{});
  const Eigen::Isometry3f identity = Eigen::Isometry3f::Identity();
  // On the wall, 5 mm in front (within the 10 mm margin), and behind it: none in free space.
  EXPECT_FLOAT_EQ(check.violation(samples({{0, 1.0f}, {0.1f, 0.995f}, {0.2f, 1.2f}}), identity),
                  0.0f);
  // 5 cm in front of the wall: the sensor saw through it.
  EXPECT_FLOAT_EQ(check.violation(samples({{0, 0.95f}, {0.1f, 1.0f}}), identity), 0.5f);
  // Facing away, off the image (x = 2 m at z = 0.9 m), over the unmeasured column 0 (u = 0 at
  // x = -0.475 z): not judged.
  EXPECT_FLOAT_EQ(check.violation(samples({{0, 0.9f}}, true), identity), 0.0f);
  EXPECT_FLOAT_EQ(check.violation(samples({{2.0f, 0.9f}, {-0.475f * 0.9f, 0.9f}}), identity), 0.0f);
  // The pose moves the model: 10 cm towards the camera puts the on-wall sample in free space.
  Eigen::Isometry3f closer = Eigen::Isometry3f::Identity();
  closer.translation() = Eigen::Vector3f(0, 0, -0.1f);
  EXPECT_FLOAT_EQ(check.violation(samples({{0, 1.0f}}), closer), 1.0f);
  // Turned half around about y, the sample faces away from the camera and is not judged.
  Eigen::Isometry3f turned = Eigen::Isometry3f::Identity();
  turned.linear() = Eigen::AngleAxisf(3.14159265f, Eigen::Vector3f::UnitY()).toRotationMatrix();
  turned.translation() = Eigen::Vector3f(0, 0, 1.9f);  // puts (0, 0, 1) at z = 0.9
  EXPECT_FLOAT_EQ(check.violation(samples({{0, 1.0f}}), turned), 0.0f);
}

TEST(FreeSpaceCheck, LeavesOutSurfaceSeenEdgeOn) {
  const OrganizedCloud cloud = wall();
  const CameraIntrinsics k = camera();
  // 5 cm in front of the wall on the optical axis, its normal turned from the camera about y by
  // 88 degrees: seen edge-on, so not judged at the default grazing angle; at 90 it is.
  ObjectModel edge_on = samples({{0, 0.95f}});
  const float turn = 88.0f * 3.14159265f / 180.0f;
  edge_on.normals[0] = Eigen::Vector3f(std::sin(turn), 0, -std::cos(turn));
  const Eigen::Isometry3f identity = Eigen::Isometry3f::Identity();
  EXPECT_EQ(FreeSpaceCheck(cloud, k, FreeSpaceParams{}).compare(edge_on, identity).seen, 0);
  FreeSpaceParams every_facing;
  every_facing.grazing_angle = 90;
  EXPECT_FLOAT_EQ(FreeSpaceCheck(cloud, k, every_facing).violation(edge_on, identity), 1.0f);
  // 80 degrees from the line of sight is within the default and judged.
  const float within = 80.0f * 3.14159265f / 180.0f;
  edge_on.normals[0] = Eigen::Vector3f(std::sin(within), 0, -std::cos(within));
  EXPECT_FLOAT_EQ(FreeSpaceCheck(cloud, k, FreeSpaceParams{}).violation(edge_on, identity), 1.0f);
}

TEST(FreeSpaceCheck, ComparesTheVisibleSurfaceWithTheMeasuredOne) {
  const OrganizedCloud cloud = wall();
  const CameraIntrinsics k = camera();
  const FreeSpaceCheck check(cloud, k, FreeSpaceParams{});
  cv::Mat probability(kSize, kSize, CV_32FC1, cv::Scalar(0.25f));
  probability.at<float>(10, 10) = 0.75f;  // the pixel of (0.025, 0, 1), see below
  // On the wall (two, 0 and 4 mm off), 5 cm in front (free), 5 cm behind (occluded).
  const SurfaceComparison c =
      check.compare(samples({{0.025f, 1.0f}, {0.1f, 1.004f}, {0.2f, 0.95f}, {0.3f, 1.05f}}),
                    Eigen::Isometry3f::Identity(), &probability);
  EXPECT_EQ(c.seen, 4);
  EXPECT_EQ(c.free, 1);
  EXPECT_EQ(c.confirmed, 2);
  EXPECT_NEAR(c.support, 0.75 + 0.25, 1e-6);
  // Without a map the counts stay and the support is zero.
  EXPECT_EQ(check.compare(samples({{0, 1.0f}}), Eigen::Isometry3f::Identity()).support, 0.0);
}

TEST(FreeSpaceCheck, RejectsBadParametersAndMismatchedIntrinsics) {
  const OrganizedCloud cloud = wall();
  const CameraIntrinsics k = camera();
  EXPECT_THROW(FreeSpaceCheck(cloud, k, FreeSpaceParams{true, 0.0f}), InputError);
  EXPECT_THROW(FreeSpaceCheck(cloud, k, FreeSpaceParams{true, 0.5f}), InputError);
  EXPECT_THROW(FreeSpaceCheck(cloud, k, FreeSpaceParams{true, 0.01f, 95.0f}), InputError);
  CameraIntrinsics wrong = k;
  wrong.width = 640;
  EXPECT_THROW(FreeSpaceCheck(cloud, wrong, FreeSpaceParams{}), InputError);
}

}  // namespace
}  // namespace stocs
