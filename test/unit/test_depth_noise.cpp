// The depth sensor model: noise growing with depth, quantisation steps, pixels lost at depth edges
// and on grazing surfaces, determinism.
#include <gtest/gtest.h>

#include "stocs/sim/depth_noise.h"
#include "stocs/sim/depth_renderer.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

/// A large plate facing the camera at `z`, turned by `tilt` radians about the image's y axis.
DepthRenderer plate(float z, float tilt = 0) {
  DepthRenderer r(test::smallCamera());
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.translation() = Eigen::Vector3f(0, 0, z);
  pose.linear() = Eigen::AngleAxisf(tilt, Eigen::Vector3f::UnitY()).toRotationMatrix();
  r.draw(boxMesh({z, z, 0.001f}), pose, 1);
  return r;
}

/// Standard deviation of measured minus true depth over the pixels that kept a depth.
double errorStd(const cv::Mat& measured, const cv::Mat& truth) {
  const cv::Mat kept = measured > 0;
  cv::Scalar mean, stddev;
  cv::meanStdDev(measured - truth, mean, stddev, kept);
  return stddev[0];
}

DepthNoiseParams noiseOnly() {
  DepthNoiseParams p;
  p.quantisation = 0;
  p.edge_dropout = 0;
  p.dropout = 0;
  return p;
}

TEST(DepthNoise, NoiseGrowsWithDepthAsTheSensorModelSays) {
  const DepthNoiseParams p = noiseOnly();
  double sigma[2];
  const float depths[2] = {0.5f, 1.5f};
  for (int k = 0; k < 2; ++k) {
    const DepthRenderer r = plate(depths[k]);
    sigma[k] =
        errorStd(applyDepthNoise(r.depth(), r.normals(), test::smallCamera(), p, 1), r.depth());
    const double model = 0.0012 + 0.0019 * (depths[k] - 0.4) * (depths[k] - 0.4);
    EXPECT_NEAR(sigma[k], model, 0.1 * model) << "at " << depths[k] << " m";
  }
  EXPECT_GT(sigma[1], 2 * sigma[0]);
}

TEST(DepthNoise, QuantisationStepsGrowWithDepthSquared) {
  DepthNoiseParams p;
  p.sigma_min = p.sigma_quadratic = 0;
  p.edge_dropout = p.dropout = 0;
  const float depths[2] = {0.8f, 2.0f};
  for (int k = 0; k < 2; ++k) {
    // A slanted plate spans many depths; measured values fall on levels one step apart.
    const DepthRenderer r = plate(depths[k], 0.25f);
    const cv::Mat d = applyDepthNoise(r.depth(), r.normals(), test::smallCamera(), p, 1);
    std::vector<float> levels;
    for (int v = 0; v < d.rows; ++v) {
      for (int u = 0; u < d.cols; ++u) {
        const float z = d.at<float>(v, u);
        if (z > 0 && std::abs(z - depths[k]) < 0.1f) levels.push_back(z);
      }
    }
    std::sort(levels.begin(), levels.end());
    levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
    ASSERT_GT(levels.size(), 3u);
    for (size_t i = 1; i < levels.size(); ++i) {
      // Levels 1 / (n k) apart in n: the step between z and z' is k z z', about k z^2.
      const float step = 0.0029f * levels[i] * levels[i - 1];
      ASSERT_NEAR(levels[i] - levels[i - 1], step, 0.01f * step) << "at " << levels[i] << " m";
    }
    const float exact = r.depth().at<float>(60, 80), measured = d.at<float>(60, 80);
    EXPECT_LE(std::abs(measured - exact), 0.51f * 0.0029f * exact * exact);
  }
}

TEST(DepthNoise, DepthEdgesLoseTheirPixelsAndFlatPartsKeepThem) {
  DepthRenderer r(test::smallCamera());
  Eigen::Isometry3f near = Eigen::Isometry3f::Identity(), far = near;
  near.translation() = Eigen::Vector3f(0, 0, 0.6f);
  far.translation() = Eigen::Vector3f(0, 0, 1.0f);
  r.draw(boxMesh({0.1f, 0.1f, 0.02f}), near, 1);
  r.draw(boxMesh({3, 3, 0.02f}), far, 2);
  DepthNoiseParams p = noiseOnly();
  p.edge_dropout = 1;
  const cv::Mat d = applyDepthNoise(r.depth(), r.normals(), test::smallCamera(), p, 1);
  int edge = 0, lost_edge = 0, inner = 0, lost_inner = 0;
  for (int v = 1; v + 1 < d.rows; ++v) {
    for (int u = 1; u + 1 < d.cols; ++u) {
      const int l = r.labels().at<int>(v, u);
      bool at_edge = false;
      for (int dv = -1; dv <= 1; ++dv) {
        for (int du = -1; du <= 1; ++du) at_edge |= r.labels().at<int>(v + dv, u + du) != l;
      }
      (at_edge ? edge : inner) += 1;
      (at_edge ? lost_edge : lost_inner) += d.at<float>(v, u) == 0;
    }
  }
  EXPECT_GT(edge, 100);
  EXPECT_EQ(lost_edge, edge);
  EXPECT_EQ(lost_inner, 0);
}

TEST(DepthNoise, GrazingSurfacesLoseTheirDepth) {
  // Near the image centre the viewing ray is the optical axis, so the plate's tilt is the angle.
  const cv::Rect centre(75, 0, 10, 120);
  const DepthNoiseParams p = noiseOnly();
  const DepthRenderer steep = plate(1.0f, 1.45f);  // 83 degrees
  EXPECT_GT(cv::countNonZero(steep.depth()(centre)), 50);
  const cv::Mat lost = applyDepthNoise(steep.depth(), steep.normals(), test::smallCamera(), p, 1);
  EXPECT_EQ(cv::countNonZero(lost(centre)), 0);
  const DepthRenderer tilted = plate(1.0f, 1.2f);  // 69 degrees
  const cv::Mat kept = applyDepthNoise(tilted.depth(), tilted.normals(), test::smallCamera(), p, 1);
  EXPECT_GT(cv::countNonZero(tilted.depth()(centre)), 50);
  EXPECT_EQ(cv::countNonZero(kept(centre)), cv::countNonZero(tilted.depth()(centre)));
}

TEST(DepthNoise, DeterministicPerSeedAndSilentAtLevelZero) {
  const DepthRenderer r = plate(0.8f, 0.3f);
  const DepthNoiseParams p;
  const cv::Mat a = applyDepthNoise(r.depth(), r.normals(), test::smallCamera(), p, 3);
  const cv::Mat b = applyDepthNoise(r.depth(), r.normals(), test::smallCamera(), p, 3);
  const cv::Mat c = applyDepthNoise(r.depth(), r.normals(), test::smallCamera(), p, 4);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a, c, cv::NORM_INF), 0.0);
  const cv::Mat exact =
      applyDepthNoise(r.depth(), r.normals(), test::smallCamera(), p.atLevel(0), 3);
  EXPECT_EQ(cv::norm(exact, r.depth(), cv::NORM_INF), 0.0);
  const DepthNoiseParams doubled = p.atLevel(2);
  EXPECT_FLOAT_EQ(doubled.sigma_min, 2 * p.sigma_min);
  EXPECT_FLOAT_EQ(doubled.edge_dropout, std::min(1.0f, 2 * p.edge_dropout));
}

TEST(DepthNoise, BadInputsAreRefused) {
  const DepthRenderer r = plate(0.8f);
  EXPECT_THROW(
      applyDepthNoise(r.depth()(cv::Rect(0, 0, 10, 10)), r.normals(), test::smallCamera(), {}, 0),
      InputError);
  DepthNoiseParams bad;
  bad.grazing_angle_deg = 120;
  EXPECT_THROW(applyDepthNoise(r.depth(), r.normals(), test::smallCamera(), bad, 0), InputError);
}

}  // namespace
}  // namespace stocs
