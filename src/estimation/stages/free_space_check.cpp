#include "stocs/estimation/stages/free_space_check.h"

#include <fmt/format.h>

#include <algorithm>
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
          .flag("--free-space-margin")
          .add(&FreeSpaceParams::grazing_angle, "grazing_angle", "deg",
               ParamRange::aboveUpTo(0, 90),
               "model surface seen at more than this angle from its normal is not compared")
          .flag("--free-space-grazing-angle");
  return schema;
}

void FreeSpaceParams::validate() const {
  schema().validate(*this);
}

FreeSpaceCheck::FreeSpaceCheck(const OrganizedCloud& cloud, const CameraIntrinsics& camera,
                               const FreeSpaceParams& params)
    : cloud_(cloud),
      camera_(camera),
      params_(params),
      min_facing_(std::max(0.0f, std::cos(params.grazing_angle * static_cast<float>(M_PI) / 180))) {
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
  visit(model, pose, [&](size_t, int u, int v, SampleView view) {
    ++c.seen;
    if (view == SampleView::kFree) {
      ++c.free;
    } else if (view == SampleView::kConfirmed) {
      ++c.confirmed;
      if (probability) c.support += probability->at<float>(v, u);
    }
  });
  return c;
}

}  // namespace stocs
