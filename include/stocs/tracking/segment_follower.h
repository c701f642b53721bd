#pragma once
// One tracking step of one object: the soft segment of the image box where the object is
// predicted, point-to-plane ICP from the predicted pose against it (the estimator's refiner), a
// search along the direction ICP leaves least constrained (least_constrained_slide.h), and the
// pose judged by the calibrated confidence (judgeInstance). A tracked pose has no bases, so its
// consensus evidence is 0: it must be accepted on what the frame shows of it.

#include <Eigen/Geometry>
#include <opencv2/core/types.hpp>
#include <optional>

#include "stocs/estimation/frame.h"
#include "stocs/estimation/pose_proximity.h"
#include "stocs/estimation/stages/icp_refiner.h"
#include "stocs/estimation/stages/lcp_scorer.h"

namespace stocs {

/// The image box of the model's bounding sphere (PoseProximity's centre and radius) at `pose`
/// (model to camera), widened by `margin` times its size on
/// each side and clipped to the image; the whole image when the sphere reaches behind the camera.
cv::Rect predictedBox(const PoseProximity& extent, const Eigen::Isometry3f& pose,
                      const CameraIntrinsics& camera, float margin);

class SegmentFollower {
 public:
  /// Segments `box` of the input (no instance regions). `in` and what it points to must outlive the
  /// follower.
  SegmentFollower(const ObjectInput& in, const cv::Rect& box);
  SegmentFollower(const SegmentFollower&) = delete;
  SegmentFollower& operator=(const SegmentFollower&) = delete;

  /// The pose refined from `predicted`, with its objective, covariance, evidence and verdict.
  InstancePose follow(const Eigen::Isometry3f& predicted) const;
  /// StoCS on the box's segment alone (detectOnSegment): the local search after a failure.
  PoseEstimate search() const;
  /// Whether the object at `pose` (a track's prediction, whose follow was not accepted) is hidden
  /// behind a nearer surface: of its camera-facing samples on measured pixels, at least half lie
  /// behind the measured surface, and few where the sensor sees through (nothing contradicts it).
  bool hiddenBehindNearerSurface(const Eigen::Isometry3f& pose) const;

  const SoftSegment& segment() const { return segment_; }

 private:
  const ObjectInput& in_;
  SoftSegment segment_;
  std::optional<LcpScorer> scorer_;
  std::optional<IcpRefiner> icp_;  // empty when ICP is off
};

}  // namespace stocs
