#include "stocs_ros/stocs_node/pose_uncertainty.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "stocs/estimation/stages/icp_refiner.h"

namespace stocs_ros {
namespace {

/// chi-square quantile at 0.9 with 3 degrees of freedom.
constexpr double kChiSquare3At90 = 6.251388631170325;
/// Opacity of the ellipsoid: the object stays visible inside it.
constexpr float kUncertaintyAlpha = 0.3f;

}  // namespace

stocs::PoseCovariance publishableCovariance(const stocs::PoseCovariance& covariance,
                                            const Eigen::Isometry3f& pose,
                                            const stocs::ObjectModel& model) {
  if (covariance.allFinite() && covariance.isApprox(covariance.transpose()) &&
      Eigen::LLT<stocs::PoseCovariance>(covariance).info() == Eigen::Success) {
    return covariance;
  }
  return stocs::priorCovariance(pose, (pose * stocs::sampleCentre(model)).cast<double>(),
                                model.diameter);
}

boost::array<double, 36> covarianceMsg(const stocs::PoseCovariance& covariance) {
  boost::array<double, 36> out;
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) out[static_cast<size_t>(6 * r + c)] = covariance(r, c);
  }
  return out;
}

visualization_msgs::Marker uncertaintyMarker(const Eigen::Isometry3f& pose,
                                             const stocs::PoseCovariance& covariance,
                                             std_msgs::ColorRGBA colour, double minimum_diameter) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance.topLeftCorner<3, 3>());
  Eigen::Matrix3d axes = eigen.eigenvectors();
  if (axes.determinant() < 0) axes.col(2) = -axes.col(2);  // a rotation, not a reflection
  const Eigen::Quaterniond orientation(axes);
  const Eigen::Vector3d diameters =
      (2 * (kChiSquare3At90 * eigen.eigenvalues().cwiseMax(0)).cwiseSqrt())
          .cwiseMax(minimum_diameter);
  visualization_msgs::Marker m;
  m.type = visualization_msgs::Marker::SPHERE;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.position.x = pose.translation().x();
  m.pose.position.y = pose.translation().y();
  m.pose.position.z = pose.translation().z();
  m.pose.orientation.w = orientation.w();
  m.pose.orientation.x = orientation.x();
  m.pose.orientation.y = orientation.y();
  m.pose.orientation.z = orientation.z();
  m.scale.x = diameters.x();
  m.scale.y = diameters.y();
  m.scale.z = diameters.z();
  colour.a = kUncertaintyAlpha;
  m.color = colour;
  return m;
}

}  // namespace stocs_ros
