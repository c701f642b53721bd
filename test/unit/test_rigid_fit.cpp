// Kabsch/Umeyama fit of a congruent set to its base.
#include <gtest/gtest.h>

#include "stocs/random.h"
#include "stocs/rigid_fit.h"

namespace stocs {
namespace {

const std::array<Eigen::Vector3f, 4> kModel = {
    Eigen::Vector3f(0, 0, 0), Eigen::Vector3f(0.1f, 0, 0), Eigen::Vector3f(0, 0.08f, 0.01f),
    Eigen::Vector3f(0.05f, 0.05f, 0.06f)};

Eigen::Isometry3f knownPose() {
  Eigen::Isometry3f t = Eigen::Isometry3f::Identity();
  t.linear() =
      Eigen::AngleAxisf(2.1f, Eigen::Vector3f(-1, 0.5f, 0.2f).normalized()).toRotationMatrix();
  t.translation() = Eigen::Vector3f(0.2f, -0.1f, 0.8f);
  return t;
}

TEST(RigidFit, RecoversAnExactTransform) {
  const Eigen::Isometry3f truth = knownPose();
  std::array<Eigen::Vector3f, 4> scene;
  for (int k = 0; k < 4; ++k) scene[k] = truth * kModel[k];
  float rms = -1;
  const auto fit = fitRigid(kModel, scene, 1e-3f, &rms);
  ASSERT_TRUE(fit);
  EXPECT_LT(rms, 1e-5f);
  EXPECT_TRUE(fit->matrix().isApprox(truth.matrix(), 1e-4f));
  EXPECT_NEAR(fit->linear().determinant(), 1.0f, 1e-5f);
}

TEST(RigidFit, ReportsTheResidualOfNoisyPointsAndRejectsAboveTheLimit) {
  const Eigen::Isometry3f truth = knownPose();
  std::array<Eigen::Vector3f, 4> scene;
  const Eigen::Vector3f offsets[4] = {
      {0.002f, 0, 0}, {-0.002f, 0, 0}, {0, 0.002f, 0}, {0, -0.002f, 0}};
  for (int k = 0; k < 4; ++k) scene[k] = truth * kModel[k] + offsets[k];
  float rms = -1;
  ASSERT_TRUE(fitRigid(kModel, scene, 0.005f, &rms));
  EXPECT_GT(rms, 0.0005f);
  EXPECT_LT(rms, 0.002f + 1e-6f);  // least squares cannot do worse than the true pose
  EXPECT_FALSE(fitRigid(kModel, scene, rms * 0.9f));
}

TEST(RigidFit, AMirrorImageIsNotARigidMotion) {
  // Reflection preserves all six distances but no rotation maps a tetrahedron onto its mirror.
  std::array<Eigen::Vector3f, 4> mirrored;
  for (int k = 0; k < 4; ++k)
    mirrored[k] = Eigen::Vector3f(-kModel[k].x(), kModel[k].y(), kModel[k].z());
  float rms = 0;
  EXPECT_FALSE(fitRigid(kModel, mirrored, 0.005f, &rms));
  EXPECT_GT(rms, 0.005f);
}

}  // namespace
}  // namespace stocs
