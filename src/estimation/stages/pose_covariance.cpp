#include "stocs/estimation/stages/pose_covariance.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

namespace stocs {
namespace {

constexpr int kParameters = 6;

/// Information of the prior in the rows' (w, v) order about the model's centre.
Eigen::Matrix<double, 6, 6> priorInformation(double diameter) {
  const double translation_std = std::max(diameter, 1e-3);
  Eigen::Matrix<double, 6, 1> diagonal;
  diagonal << Eigen::Vector3d::Constant(1.0 / (M_PI * M_PI)),
      Eigen::Vector3d::Constant(1.0 / (translation_std * translation_std));
  return diagonal.asDiagonal();
}

/// A covariance of (w, v) about `centre` moved to the pose's origin `origin` and reordered to
/// (translation, rotation): the origin moves by v + w x (origin - centre).
PoseCovariance atOrigin(const Eigen::Matrix<double, 6, 6>& about_centre,
                        const Eigen::Vector3d& origin, const Eigen::Vector3d& centre) {
  const Eigen::Vector3d arm = origin - centre;
  Eigen::Matrix3d cross;
  cross << 0, -arm.z(), arm.y(), arm.z(), 0, -arm.x(), -arm.y(), arm.x(), 0;
  Eigen::Matrix<double, 6, 6> a = Eigen::Matrix<double, 6, 6>::Zero();
  a.block<3, 3>(0, 0) = -cross;  // w x arm = -arm x w
  a.block<3, 3>(0, 3) = Eigen::Matrix3d::Identity();
  a.block<3, 3>(3, 0) = Eigen::Matrix3d::Identity();
  const PoseCovariance moved = a * about_centre * a.transpose();
  return 0.5 * (moved + moved.transpose());
}

/// The variance (w, v order, about the centre) that near symmetries add: each turn's angle at
/// kNearSymmetrySigmas standard deviations about its axis in the camera frame, and its shift as
/// far in position, in every direction.
Eigen::Matrix<double, 6, 6> nearSymmetrySpread(const std::vector<NearSymmetry>& near_symmetries,
                                               const Eigen::Isometry3f& pose) {
  Eigen::Matrix<double, 6, 6> spread = Eigen::Matrix<double, 6, 6>::Zero();
  for (const NearSymmetry& s : near_symmetries) {
    const Eigen::Vector3d axis = (pose.linear() * s.axis).cast<double>().normalized();
    const double std = s.angle / kNearSymmetrySigmas;
    spread.topLeftCorner<3, 3>() += std * std * axis * axis.transpose();
    const double shift_std = s.shift / kNearSymmetrySigmas;
    spread.bottomRightCorner<3, 3>() += shift_std * shift_std * Eigen::Matrix3d::Identity();
  }
  return spread;
}

PoseCovariance fromInformation(
    const Eigen::Matrix<double, 6, 6>& information, const Eigen::Isometry3f& pose,
    const Eigen::Vector3d& centre,
    const Eigen::Matrix<double, 6, 6>& spread = Eigen::Matrix<double, 6, 6>::Zero()) {
  const Eigen::LLT<Eigen::Matrix<double, 6, 6>> llt(information);
  if (llt.info() != Eigen::Success) return PoseCovariance::Constant(NAN);
  return atOrigin(llt.solve(Eigen::Matrix<double, 6, 6>::Identity()) + spread,
                  pose.translation().cast<double>(), centre);
}

}  // namespace

PoseCovariance priorCovariance(const Eigen::Isometry3f& pose, const Eigen::Vector3d& centre,
                               double diameter) {
  return fromInformation(priorInformation(diameter), pose, centre);
}

PoseCovariance poseCovariance(const PointToPlaneSystem& system, const Eigen::Isometry3f& pose,
                              double diameter, const std::vector<NearSymmetry>& near_symmetries) {
  const PoseCovariance prior = priorCovariance(pose, system.centre, diameter);
  if (system.used <= kParameters) return prior;
  // Weighted least squares with var(r_i) = sigma^2 / w_i: sigma^2 from the weighted residuals.
  const double sigma2 = std::max(system.weighted_squares / (system.used - kParameters),
                                 kMinResidualStd * kMinResidualStd) *
                        kCorrelationFactor;
  const PoseCovariance covariance =
      fromInformation(system.jtj / sigma2 + priorInformation(diameter), pose, system.centre,
                      nearSymmetrySpread(near_symmetries, pose));
  return covariance.allFinite() ? covariance : prior;
}

PoseCovariance poseCovariance(const ObjectModel& model, const IcpRefiner* icp,
                              const Eigen::Isometry3f& pose, int region, const LcpScorer* near,
                              const std::vector<NearSymmetry>& near_symmetries) {
  if (!icp) {
    return priorCovariance(pose, (pose * sampleCentre(model)).cast<double>(), model.diameter);
  }
  return poseCovariance(icp->system(model, pose, region, near), pose, model.diameter,
                        near_symmetries);
}

}  // namespace stocs
