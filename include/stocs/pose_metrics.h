#pragma once
// Pose error metrics on model points (units are those of the points and translations).
//   ADD:   mean distance between corresponding model points under the two poses.
//   ADD-S: mean distance from each point under the estimate to the closest point under the truth,
//          which forgives any symmetry of the shape.

#include <Eigen/Geometry>
#include <vector>

namespace stocs {

struct RigidPose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
};

double addError(const std::vector<Eigen::Vector3f>& model_points, const RigidPose& estimate,
                const RigidPose& truth);

double addsError(const std::vector<Eigen::Vector3f>& model_points, const RigidPose& estimate,
                 const RigidPose& truth);

}  // namespace stocs
