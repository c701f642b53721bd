// The pose covariance on segments made of a model's own camera-facing samples with noise along
// their normals: finite and positive definite, small where the surface pins the pose, the prior's
// where it does not (about a cylinder's axis) or the model almost repeats itself (a near
// symmetry), scaled with the noise, and the prior's whenever the data give nothing usable.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "stocs/estimation/stages/pose_covariance.h"
#include "stocs/sim/object_catalogue.h"
#include "stocs/sim/shape_meshes.h"
#include "test_support.h"

namespace stocs {
namespace {

/// The samples of `model` at `pose` facing the camera, moved along their normals by Gaussian noise
/// of `noise` metres, as a segment of uniform confidence.
SoftSegment noisySamples(const ObjectModel& model, const Eigen::Isometry3f& pose, float noise) {
  std::mt19937 random(7);
  std::normal_distribution<float> gauss(0.0f, noise);
  SoftSegment segment;
  for (size_t i = 0; i < model.size(); ++i) {
    const Eigen::Vector3f n = pose.linear() * model.normals[i];
    const Eigen::Vector3f p = pose * model.points[i];
    if (n.dot(p) >= 0) continue;
    segment.points.push_back(p + gauss(random) * n);
    segment.normals.push_back(n);
    segment.confidence.push_back(1.0f);
    segment.pixel.push_back(static_cast<int>(i));
  }
  segment.probability.assign(segment.size(), 1.0f / static_cast<float>(segment.size()));
  return segment;
}

PoseCovariance covarianceOf(const ObjectModel& model, const SoftSegment& segment,
                            const Eigen::Isometry3f& pose) {
  const IcpRefiner icp(segment, IcpParams{});
  return poseCovariance(model, &icp, pose, -1);
}

PoseCovariance covarianceOn(const ObjectModel& model, const Eigen::Isometry3f& pose, float noise) {
  return covarianceOf(model, noisySamples(model, pose, noise), pose);
}

void expectPositiveDefinite(const PoseCovariance& c) {
  ASSERT_TRUE(c.allFinite());
  EXPECT_TRUE(c.isApprox(c.transpose()));
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<PoseCovariance>(c).eigenvalues().minCoeff(), 0);
}

TEST(PoseCovariance, AnAsymmetricObjectIsPinnedInEveryDirection) {
  const ObjectModel model = prepareModel(asymmetricMesh(), ModelSamplingParams{});
  const PoseCovariance c = covarianceOn(model, test::viewingPose(0.8f), 0.001f);
  expectPositiveDefinite(c);
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(std::sqrt(c(i, i)), 0.003) << "translation " << i;
    EXPECT_LT(std::sqrt(c(3 + i, 3 + i)), 0.05) << "rotation " << i;
  }
}

TEST(PoseCovariance, RotationAboutACylindersAxisKeepsThePriorsVariance) {
  const ObjectModel model = prepareModel(cylinderMesh(0.03f, 0.1f, 48), ModelSamplingParams{});
  const Eigen::Isometry3f pose = test::viewingPose(0.8f);
  SoftSegment segment = noisySamples(model, pose, 0.001f);
  // The sensor sees a round surface, not the mesh's 48 facets: radial normals on the side.
  for (size_t i = 0; i < segment.size(); ++i) {
    const Eigen::Vector3f q = pose.inverse() * segment.points[i];
    if (q.z() > 0.001f && q.z() < 0.099f) {
      segment.normals[i] = pose.linear() * Eigen::Vector3f(q.x(), q.y(), 0).normalized();
    }
  }
  const PoseCovariance c = covarianceOf(model, segment, pose);
  expectPositiveDefinite(c);
  const Eigen::Matrix3d rotation = c.bottomRightCorner<3, 3>();
  const Eigen::Vector3d axis = (pose.linear() * Eigen::Vector3f::UnitZ()).cast<double>();
  const Eigen::Vector3d across = axis.unitOrthogonal();
  EXPECT_GT(axis.dot(rotation * axis), 1.0);  // a std above 1 rad: the data hardly say
  EXPECT_LT(across.dot(rotation * across), 0.05 * 0.05);
}

TEST(PoseCovariance, ANearSymmetryPutsItsTurnAndShiftAtTwoStandardDeviations) {
  const ObjectModel model = prepareModel(asymmetricMesh(), ModelSamplingParams{});
  const Eigen::Isometry3f pose = test::viewingPose(0.8f);
  const SoftSegment segment = noisySamples(model, pose, 0.001f);
  const IcpRefiner icp(segment, IcpParams{});
  const NearSymmetry quarter{Eigen::Vector3f::UnitX(), static_cast<float>(M_PI / 2), 0.004f};
  const PoseCovariance c = poseCovariance(model, &icp, pose, -1, nullptr, {quarter});
  expectPositiveDefinite(c);
  const Eigen::Matrix3d rotation = c.bottomRightCorner<3, 3>();
  const Eigen::Vector3d axis = (pose.linear() * Eigen::Vector3f::UnitX()).cast<double>();
  EXPECT_NEAR(std::sqrt(axis.dot(rotation * axis)), M_PI / 4, 0.01);
  // Across the axis the data still pin the rotation; the position is known to about the shift.
  const Eigen::Vector3d across = (pose.linear() * Eigen::Vector3f::UnitY()).cast<double>();
  EXPECT_LT(across.dot(rotation * across), 0.05 * 0.05);
  for (int i = 0; i < 3; ++i) EXPECT_GT(std::sqrt(c(i, i)), 0.002) << "translation " << i;
}

TEST(PoseCovariance, ScalesWithTheResidualNoise) {
  const ObjectModel model = prepareModel(asymmetricMesh(), ModelSamplingParams{});
  const Eigen::Isometry3f pose = test::viewingPose(0.8f);
  const double low = covarianceOn(model, pose, 0.001f).trace();
  const double high = covarianceOn(model, pose, 0.002f).trace();
  EXPECT_GT(high / low, 3.0);
  EXPECT_LT(high / low, 5.0);
}

TEST(PoseCovariance, ThePriorIsAboutTheCentreMovedToThePosesOrigin) {
  const Eigen::Isometry3f pose = test::viewingPose(0.8f);
  const Eigen::Vector3d centre = pose.translation().cast<double>() + Eigen::Vector3d(0, 0.1, 0);
  const PoseCovariance c = priorCovariance(pose, centre, 0.2);
  expectPositiveDefinite(c);
  // The origin lies 0.1 m from the centre along -y: a rotation about x or z swings it.
  EXPECT_NEAR(c(0, 0), 0.2 * 0.2 + M_PI * M_PI * 0.01, 1e-9);
  EXPECT_NEAR(c(1, 1), 0.2 * 0.2, 1e-9);
  EXPECT_NEAR(c(3, 3), M_PI * M_PI, 1e-9);
  EXPECT_NEAR(c(0, 5), M_PI * M_PI * 0.1, 1e-9);  // dx = w_z * 0.1 (w x (0, -0.1, 0))
  EXPECT_NEAR(c(1, 5), 0, 1e-12);
}

TEST(PoseCovariance, NothingUsableGivesThePrior) {
  const ObjectModel model = prepareModel(asymmetricMesh(), ModelSamplingParams{});
  const Eigen::Isometry3f pose = test::viewingPose(0.8f);
  const Eigen::Vector3d centre = (pose * sampleCentre(model)).cast<double>();
  const PoseCovariance prior = priorCovariance(pose, centre, model.diameter);
  PointToPlaneSystem broken;
  broken.centre = centre;
  broken.used = 100;
  broken.jtj(2, 2) = NAN;
  EXPECT_TRUE(poseCovariance(broken, pose, model.diameter).isApprox(prior));
  PointToPlaneSystem few;
  few.centre = centre;
  few.used = 5;
  EXPECT_TRUE(poseCovariance(few, pose, model.diameter).isApprox(prior));
  EXPECT_TRUE(poseCovariance(model, nullptr, pose, -1).isApprox(prior));
}

}  // namespace
}  // namespace stocs
