#include "stocs/eval/symmetries.h"

#include <fmt/format.h>

#include <cmath>

#include "stocs/util/error.h"

namespace stocs {

std::vector<RigidPose> symmetryTransformations(const BopObjectInfo& info, int continuous_steps) {
  if (continuous_steps < 1) {
    throw InputError(fmt::format("continuous symmetry steps {} is below 1", continuous_steps));
  }
  std::vector<RigidPose> discrete = {RigidPose{}};
  for (const Eigen::Matrix4d& m : info.symmetries_discrete) {
    discrete.push_back({m.topLeftCorner<3, 3>(), m.topRightCorner<3, 1>()});
  }
  std::vector<RigidPose> continuous;
  for (const ContinuousSymmetry& s : info.symmetries_continuous) {
    if (!(s.axis.norm() > 0)) throw InputError("continuous symmetry without a valid axis");
    for (int i = 0; i < continuous_steps; ++i) {
      const Eigen::Matrix3d R =
          Eigen::AngleAxisd(2 * M_PI * i / continuous_steps, s.axis.normalized())
              .toRotationMatrix();
      // Rotation about the axis through `offset`: x -> R (x - offset) + offset.
      continuous.push_back({R, s.offset_mm - R * s.offset_mm});
    }
  }
  if (continuous.empty()) return discrete;
  std::vector<RigidPose> group;
  for (const RigidPose& d : discrete) {
    for (const RigidPose& c : continuous) group.push_back({c.R * d.R, c.R * d.t + c.t});
  }
  return group;
}

}  // namespace stocs
