#pragma once
// Whether a pose covariance is honest: the share of true pose errors inside its 50% and 90%
// confidence ellipsoids. The error is a 6-vector in the covariance's convention
// (InstancePose::covariance): the translation of the pose's origin in metres, then the rotation
// vector of R_estimate R_truth^T in radians, both in the camera frame. For a symmetric object the
// truth is its nearest symmetric equivalent (by the Mahalanobis distance under the covariance).
// For a Gaussian error the squared Mahalanobis distance is chi-square with 6 degrees of freedom,
// so a share p of errors should lie where its CDF is at most p.

#include <Eigen/Core>
#include <map>
#include <vector>

#include "stocs/eval/dataset_evaluation.h"
#include "stocs/eval/pose_metrics.h"

namespace stocs {

using PoseError = Eigen::Matrix<double, 6, 1>;
using PoseCovarianceMatrix = Eigen::Matrix<double, 6, 6>;

/// The error of `estimate` against `truth` (BOP poses, translations in mm), metres and radians.
PoseError poseError(const RigidPose& estimate, const RigidPose& truth);

/// e^T covariance^-1 e, or infinity when the covariance is not positive definite.
double mahalanobisSquared(const PoseError& error, const PoseCovarianceMatrix& covariance);

/// The smallest squared Mahalanobis distance of `estimate` to `truth` composed with any of
/// `symmetries` (symmetryTransformations; the identity alone for an asymmetric object).
double nearestSymmetricMahalanobis(const RigidPose& estimate, const RigidPose& truth,
                                   const std::vector<RigidPose>& symmetries,
                                   const PoseCovarianceMatrix& covariance);

/// The chi-square CDF with 6 degrees of freedom: 1 - e^(-x/2) (1 + x/2 + x^2/8).
double chiSquare6Cdf(double x);

struct EllipsoidCoverage {
  int poses = 0;        ///< errors counted
  double within50 = 0;  ///< share inside the 50% ellipsoid
  double within90 = 0;  ///< share inside the 90% ellipsoid
};

/// The shares of squared Mahalanobis distances inside the 50% and 90% ellipsoids.
EllipsoidCoverage ellipsoidCoverage(const std::vector<double>& squared_distances);

/// The coverage over the correct estimates (ADD-S below 10% of the diameter) of `targets` that
/// have a covariance in `covariances` (all-zero ones, from methods without a covariance, are left
/// out), with each object's symmetries from `info`.
EllipsoidCoverage correctPoseCoverage(const std::vector<TargetResult>& targets,
                                      const std::map<Target, PoseCovarianceMatrix>& covariances,
                                      const std::map<int, BopObjectInfo>& info);

}  // namespace stocs
