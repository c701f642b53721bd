#include "stocs/eval/rt_error.h"

#include <cmath>
#include <limits>

namespace stocs {

RollPitchYaw rollPitchYaw(const Eigen::Matrix3d& R) {
  RollPitchYaw a;
  const double cos_pitch = std::hypot(R(0, 0), R(1, 0));
  a.pitch = std::atan2(-R(2, 0), cos_pitch);
  if (cos_pitch > 1e-9) {
    a.roll = std::atan2(R(2, 1), R(2, 2));
    a.yaw = std::atan2(R(1, 0), R(0, 0));
  } else {
    // Gimbal lock: only roll - yaw (pitch +90) or roll + yaw (pitch -90) is defined; yaw = 0.
    a.roll = std::atan2(-R(1, 2), R(1, 1));
  }
  return a;
}

double eulerErrorDeg(const Eigen::Matrix3d& truth, const Eigen::Matrix3d& estimate) {
  const RollPitchYaw a = rollPitchYaw(truth.transpose() * estimate);
  return (std::abs(a.roll) + std::abs(a.pitch) + std::abs(a.yaw)) / 3 * 180 / M_PI;
}

RtError rtError(const RigidPose& estimate, const RigidPose& truth,
                const std::vector<RigidPose>& symmetries) {
  const std::vector<RigidPose> identity_only = {RigidPose{}};
  RtError best{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  for (const RigidPose& s : symmetries.empty() ? identity_only : symmetries) {
    // The truth composed with a symmetry shows the same surface: x -> R (R_s x + t_s) + t.
    const RtError e{eulerErrorDeg(truth.R * s.R, estimate.R),
                    (estimate.t - (truth.R * s.t + truth.t)).norm()};
    if (e.rotation_deg < best.rotation_deg ||
        (e.rotation_deg == best.rotation_deg && e.translation_mm < best.translation_mm)) {
      best = e;
    }
  }
  return best;
}

}  // namespace stocs
