#include "stocs/estimation/free_space_check.h"

#include <fmt/format.h>

#include <cmath>

#include "stocs/util/error.h"

namespace stocs {

const ParamSet<FreeSpaceParams>& FreeSpaceParams::schema() {
  static const ParamSet<FreeSpaceParams> schema =
      ParamSet<FreeSpaceParams>()
          .add(&FreeSpaceParams::enabled, "enabled",
               "rank refined poses down by their surface where the sensor sees through")
          .flag("--free-space")
          .add(&FreeSpaceParams::margin, "margin", "m", ParamRange::aboveUpTo(0, 0.1),
               "a model point this far in front of the measured surface is in free space")
          .flag("--free-space-margin");
  return schema;
}

void FreeSpaceParams::validate() const {
  schema().validate(*this);
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
