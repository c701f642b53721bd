// The coverage check of pose covariances: the error convention, the chi-square levels, and a
// Gaussian sample whose 50% and 90% ellipsoids hold 50% and 90% of it.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <random>

#include "stocs/eval/covariance_coverage.h"

namespace stocs {
namespace {

/// A small rotation vector `w` (camera frame) and translation `t` (m) applied to `truth`.
RigidPose perturbed(const RigidPose& truth, const PoseError& e) {
  const Eigen::Vector3d w = e.tail<3>();
  const Eigen::Matrix3d R = w.norm() > 0
                                ? Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix()
                                : Eigen::Matrix3d::Identity();
  return {R * truth.R, truth.t + 1000 * e.head<3>()};
}

RigidPose someTruth() {
  return {Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix(),
          Eigen::Vector3d(30, -20, 700)};
}

TEST(CovarianceCoverage, TheErrorIsTranslationInMetresThenTheCameraFrameRotationVector) {
  PoseError e;
  e << 0.002, -0.001, 0.003, 0.01, -0.02, 0.03;
  const PoseError got = poseError(perturbed(someTruth(), e), someTruth());
  EXPECT_LT((got - e).norm(), 1e-9);
}

TEST(CovarianceCoverage, ChiSquareWithSixDegreesOfFreedom) {
  EXPECT_NEAR(chiSquare6Cdf(5.348120627), 0.5, 1e-8);
  EXPECT_NEAR(chiSquare6Cdf(10.64464068), 0.9, 1e-8);
  EXPECT_EQ(chiSquare6Cdf(0), 0);
  EXPECT_EQ(chiSquare6Cdf(NAN), 0);
}

TEST(CovarianceCoverage, AGaussianSampleFillsItsEllipsoidsAsItShould) {
  PoseCovarianceMatrix covariance;
  const Eigen::Matrix<double, 6, 6> a = Eigen::Matrix<double, 6, 6>::Random() * 0.01;
  covariance = a * a.transpose() + 1e-6 * PoseCovarianceMatrix::Identity();
  const Eigen::Matrix<double, 6, 6> root = covariance.llt().matrixL();
  std::mt19937 random(3);
  std::normal_distribution<double> gauss;
  std::vector<double> distances;
  const RigidPose truth = someTruth();
  for (int i = 0; i < 20000; ++i) {
    PoseError z;
    for (int k = 0; k < 6; ++k) z(k) = gauss(random);
    const RigidPose estimate = perturbed(truth, root * z);
    distances.push_back(nearestSymmetricMahalanobis(estimate, truth, {RigidPose{}}, covariance));
  }
  const EllipsoidCoverage c = ellipsoidCoverage(distances);
  EXPECT_EQ(c.poses, 20000);
  EXPECT_NEAR(c.within50, 0.5, 0.015);
  EXPECT_NEAR(c.within90, 0.9, 0.01);
  // A covariance twice too small holds far fewer.
  for (double& d : distances) d *= 2;
  EXPECT_LT(ellipsoidCoverage(distances).within90, 0.7);
}

TEST(CovarianceCoverage, ASymmetricObjectIsMeasuredToItsNearestEquivalent) {
  const RigidPose truth = someTruth();
  const RigidPose half_turn{Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix(),
                            Eigen::Vector3d::Zero()};
  PoseError e;
  e << 0.001, 0, 0, 0, 0.01, 0;
  const RigidPose estimate = perturbed({truth.R * half_turn.R, truth.t}, e);
  const PoseCovarianceMatrix covariance = PoseCovarianceMatrix::Identity() * 1e-4;
  EXPECT_GT(nearestSymmetricMahalanobis(estimate, truth, {RigidPose{}}, covariance), 1e4);
  EXPECT_NEAR(nearestSymmetricMahalanobis(estimate, truth, {RigidPose{}, half_turn}, covariance),
              e.squaredNorm() / 1e-4, 1e-6);
  EXPECT_TRUE(std::isinf(mahalanobisSquared(e, PoseCovarianceMatrix::Zero())));
}

}  // namespace
}  // namespace stocs
