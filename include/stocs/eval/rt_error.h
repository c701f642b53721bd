#pragma once
// Rotation and translation error of a pose, the protocol of the paper's APC table (Table 1a): the
// rotation error is the mean of the absolute roll, pitch and yaw errors, the translation error the
// distance between the positions.
//
// Euler convention: the error rotation E = R_truth^T R_estimate (the estimate seen from the truth's
// model frame) is decomposed as E = Rz(yaw) Ry(pitch) Rx(roll), fixed axes x, y, z, pitch in
// [-90, 90] degrees and roll, yaw in (-180, 180] (the ROS tf `getRPY` convention); at pitch = +-90
// degrees yaw is taken as 0.

#include <Eigen/Core>
#include <vector>

#include "stocs/eval/pose_metrics.h"

namespace stocs {

struct RollPitchYaw {
  double roll = 0, pitch = 0, yaw = 0;  ///< radians
};

/// The angles of R = Rz(yaw) Ry(pitch) Rx(roll) for a rotation matrix R.
RollPitchYaw rollPitchYaw(const Eigen::Matrix3d& R);

/// (|roll| + |pitch| + |yaw|) / 3 of R_truth^T R_estimate, in degrees.
double eulerErrorDeg(const Eigen::Matrix3d& truth, const Eigen::Matrix3d& estimate);

struct RtError {
  double rotation_deg = 0;
  double translation_mm = 0;
};

/// The error against the nearest pose equivalent to `truth` under the object's symmetry group
/// (`symmetries`, see symmetryTransformations; an empty list means identity only): the smallest
/// rotation error, with the translation error of that same equivalent pose (the smaller one on a
/// tie), so that one pose of the group meets both error bounds of a success.
RtError rtError(const RigidPose& estimate, const RigidPose& truth,
                const std::vector<RigidPose>& symmetries);

}  // namespace stocs
