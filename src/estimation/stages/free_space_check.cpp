#include "stocs/estimation/stages/free_space_check.h"

#include <fmt/format.h>

#include <cmath>
#include <opencv2/core.hpp>

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
  const SurfaceComparison c = compare(model, pose);
  return c.seen == 0 ? 0.0f : static_cast<float>(c.free) / static_cast<float>(c.seen);
}

SurfaceComparison FreeSpaceCheck::compare(const ObjectModel& model, const Eigen::Isometry3f& pose,
                                          const cv::Mat* probability) const {
  SurfaceComparison c;
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
    ++c.seen;
    const float behind = cloud_.points[index].z() - p.z();
    if (behind > params_.margin) {
      ++c.free;
    } else if (behind >= -params_.margin) {  // farther in front of the sample: occluded
      ++c.confirmed;
      if (probability) c.support += probability->at<float>(v, u);
    }
  }
  return c;
}

}  // namespace stocs
