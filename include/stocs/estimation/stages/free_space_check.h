#pragma once
// Free-space check of a pose hypothesis: the share of the model's camera-facing surface samples
// that the pose puts in front of what the sensor measured, i.e. in space the sensor sees through.
// StoCS's objective (LCP) only rewards segment points a pose explains and never penalises model
// surface where there is demonstrably nothing, so two poses that explain the segment alike (a
// mug with its handle turned into the open, a box slid off its face) score the same; this check
// tells them apart. It needs the organized cloud, not just the segment.

#include <Eigen/Geometry>
#include <cmath>

#include "stocs/geometry/camera.h"
#include "stocs/geometry/organized_cloud.h"
#include "stocs/model/object_model.h"
#include "stocs/util/param_set.h"

namespace cv {
class Mat;
}

namespace stocs {

struct FreeSpaceParams {
  /// Rank the refined candidates by their objective times the share of their camera-facing
  /// surface that is not in free space (see StocsEstimator::search).
  bool enabled = true;
  /// A model sample is in free space when the measured surface at its pixel lies more than this
  /// far behind it (metres): depth noise and model error stay below it.
  float margin = 0.01f;
  /// Samples seen at more than this angle between their normal and the line of sight are not
  /// compared (degrees; 90: every camera-facing sample): a refined pose is a few degrees off, which
  /// turns a face seen edge-on towards the camera, its samples onto the background's pixels.
  float grazing_angle = 85.0f;

  /// Key, range, unit and meaning of every field (docs/parameters.md).
  static const ParamSet<FreeSpaceParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
};

/// How a pose's visible surface compares with the measured depth (FreeSpaceCheck::compare).
struct SurfaceComparison {
  int seen = 0;        ///< camera-facing model samples projecting onto a measured pixel
  int free = 0;        ///< of those, in front of the measured surface by more than the margin
  int confirmed = 0;   ///< of those, within the margin of the measured surface
  double support = 0;  ///< sum of the probability map at the confirmed samples' pixels
};

/// Where a camera-facing model sample projecting onto a measured pixel lies
/// (FreeSpaceCheck::visit).
enum class SampleView {
  kFree,  ///< in front of the measured surface by more than the margin: the sensor sees through
  kConfirmed,  ///< within the margin of the measured surface
  kOccluded,   ///< behind the measured surface by more than the margin
};

class FreeSpaceCheck {
 public:
  /// Keeps references: `cloud` and `camera` (its intrinsics) must outlive the check.
  FreeSpaceCheck(const OrganizedCloud& cloud, const CameraIntrinsics& camera,
                 const FreeSpaceParams& params);
  FreeSpaceCheck(OrganizedCloud&&, const CameraIntrinsics&, const FreeSpaceParams&) = delete;
  FreeSpaceCheck(const OrganizedCloud&, CameraIntrinsics&&, const FreeSpaceParams&) = delete;

  /// Of the model samples that face the camera at `pose` (model to camera) and project onto a
  /// pixel with a measurement, the fraction in free space; 0 when none qualifies.
  float violation(const ObjectModel& model, const Eigen::Isometry3f& pose) const;

  /// The counts behind violation(), and the agreement of the rest with the measured surface;
  /// `probability` (CV_32FC1, the cloud's size), when given, is read at the confirmed pixels.
  SurfaceComparison compare(const ObjectModel& model, const Eigen::Isometry3f& pose,
                            const cv::Mat* probability = nullptr) const;

  /// Calls `f(sample index, u, v, SampleView)` for each model sample that faces the camera at
  /// `pose` within the grazing angle and projects onto pixel (u, v) with a measurement: the samples
  /// compare() counts.
  template <class F>
  void visit(const ObjectModel& model, const Eigen::Isometry3f& pose, F&& f) const;

  const CameraIntrinsics& camera() const { return camera_; }
  const OrganizedCloud& cloud() const { return cloud_; }

 private:
  const OrganizedCloud& cloud_;
  const CameraIntrinsics& camera_;
  FreeSpaceParams params_;
  float min_facing_;  ///< cosine of the grazing angle
};

template <class F>
void FreeSpaceCheck::visit(const ObjectModel& model, const Eigen::Isometry3f& pose, F&& f) const {
  for (size_t i = 0; i < model.size(); ++i) {
    const Eigen::Vector3f p = pose * model.points[i];
    // Samples on the far side of the object are hidden by the object itself; those seen edge-on
    // tell nothing reliable.
    if (p.z() <= 0 || -(pose.linear() * model.normals[i]).dot(p) <= min_facing_ * p.norm()) {
      continue;
    }
    const Eigen::Vector2f uv = camera_.project(p);
    const int u = static_cast<int>(std::lround(uv.x()));
    const int v = static_cast<int>(std::lround(uv.y()));
    if (u < 0 || v < 0 || u >= cloud_.width || v >= cloud_.height) continue;
    const int index = v * cloud_.width + u;
    if (!cloud_.isValid(index)) continue;  // no measurement: nothing is known there
    const float behind = cloud_.points[index].z() - p.z();
    f(i, u, v,
      behind > params_.margin     ? SampleView::kFree
      : behind >= -params_.margin ? SampleView::kConfirmed
                                  : SampleView::kOccluded);
  }
}

}  // namespace stocs
