// Kabsch/Umeyama fit of a congruent set to its base.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "stocs/geometry/rigid_fit.h"
#include "stocs/util/random.h"

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

TEST(RigidFit, AgreesWithUmeyamaOnNoisyAndPlanarSets) {
  // The hand-written quaternion fit against Eigen's SVD-based one: random sets of centimetre
  // scale, a third of them planar (as most bases are), with noise from none to 5 mm.
  Rng rng(3);
  auto coordinate = [&](float spread) { return (uniform01(rng) - 0.5f) * 2 * spread; };
  for (int trial = 0; trial < 300; ++trial) {
    std::array<Eigen::Vector3f, 4> model, scene;
    for (Eigen::Vector3f& p : model) {
      p = {coordinate(0.06f), coordinate(0.06f), trial % 3 == 0 ? 0.0f : coordinate(0.06f)};
    }
    const Eigen::Quaternionf q(coordinate(1), coordinate(1), coordinate(1), coordinate(1));
    Eigen::Isometry3f truth = Eigen::Isometry3f::Identity();
    truth.linear() = q.normalized().toRotationMatrix();
    truth.translation() = Eigen::Vector3f(coordinate(0.3f), coordinate(0.3f), 0.8f);
    const float noise = 0.005f * static_cast<float>(trial % 4) / 3;
    for (int k = 0; k < 4; ++k) {
      scene[k] = truth * model[k] + Eigen::Vector3f(coordinate(noise), coordinate(noise), 0);
    }
    Eigen::Matrix<double, 3, 4> src, dst;
    for (int k = 0; k < 4; ++k) {
      src.col(k) = model[k].cast<double>();
      dst.col(k) = scene[k].cast<double>();
    }
    const Eigen::Matrix4d reference = Eigen::umeyama(src, dst, false);
    const auto fit = fitRigid(model, scene, 1.0f);
    ASSERT_TRUE(fit) << trial;
    EXPECT_LT((fit->matrix().cast<double>() - reference).cwiseAbs().maxCoeff(), 1e-5) << trial;
  }
}

TEST(RigidFit, CollinearPointsStillGetAFitWithTheirResidual) {
  // Any rotation about the line fits alike; one is returned, with an exact residual of zero.
  const std::array<Eigen::Vector3f, 4> line = {
      Eigen::Vector3f(0, 0, 0), Eigen::Vector3f(0.02f, 0, 0), Eigen::Vector3f(0.05f, 0, 0),
      Eigen::Vector3f(0.09f, 0, 0)};
  std::array<Eigen::Vector3f, 4> moved;
  for (int k = 0; k < 4; ++k) moved[k] = knownPose() * line[k];
  float rms = -1;
  const auto fit = fitRigid(line, moved, 1e-3f, &rms);
  ASSERT_TRUE(fit);
  EXPECT_LT(rms, 1e-5f);
  EXPECT_NEAR(fit->linear().determinant(), 1.0f, 1e-5f);
}

TEST(RigidFit, CoincidentPointsGetAFitThatMovesThemOntoTheScene) {
  const std::array<Eigen::Vector3f, 4> point = {
      Eigen::Vector3f(0.01f, 0.02f, 0.03f), Eigen::Vector3f(0.01f, 0.02f, 0.03f),
      Eigen::Vector3f(0.01f, 0.02f, 0.03f), Eigen::Vector3f(0.01f, 0.02f, 0.03f)};
  std::array<Eigen::Vector3f, 4> moved;
  for (int k = 0; k < 4; ++k) moved[k] = point[k] + Eigen::Vector3f(0.1f, 0, 0.5f);
  float rms = -1;
  const auto fit = fitRigid(point, moved, 1e-3f, &rms);
  ASSERT_TRUE(fit);
  EXPECT_LT(rms, 1e-6f);
  EXPECT_NEAR(fit->linear().determinant(), 1.0f, 1e-5f);
}

}  // namespace
}  // namespace stocs
