#include "stocs/free_space_check.h"

#include <fmt/format.h>

#include <cmath>

#include "stocs/error.h"

namespace stocs {

void FreeSpaceParams::validate() const {
  if (!(margin > 0.0f && margin <= 0.1f)) {
    throw InputError(fmt::format("free-space margin {} m is outside (0, 0.1]", margin));
  }
}

FreeSpaceCheck::FreeSpaceCheck(const OrganizedCloud& cloud, const CameraIntrinsics& camera,
                               const FreeSpaceParams& params)
    : cloud_(cloud), camera_(camera), params_(params) {
  params_.validate();
  if (camera.width != cloud.width || camera.height != cloud.height) {
    throw InputError(fmt::format("camera intrinsics are for {}x{} images but the cloud is {}x{}",
                                 camera.width, camera.height, cloud.width, cloud.height));
  }
}

float FreeSpaceCheck::violation(const ObjectModel& model, const Eigen::Isometry3f& pose) const {
  int seen = 0, free = 0;
  for (size_t i = 0; i < model.size(); ++i) {
    const Eigen::Vector3f p = pose * model.points[i];
    // Samples on the far side of the object are hidden by the object itself.
    if (p.z() <= 0 || (pose.linear() * model.normals[i]).dot(p) >= 0) continue;
    const Eigen::Vector2f uv = camera_.project(p);
    const int u = static_cast<int>(std::lround(uv.x()));
    const int v = static_cast<int>(std::lround(uv.y()));
    if (u < 0 || v < 0 || u >= cloud_.width || v >= cloud_.height) continue;
    const int index = v * cloud_.width + u;
    if (!cloud_.isValid(index)) continue;  // no measurement: nothing is known there
    ++seen;
    if (cloud_.points[index].z() > p.z() + params_.margin) ++free;
  }
  return seen == 0 ? 0.0f : static_cast<float>(free) / static_cast<float>(seen);
}

}  // namespace stocs
