#include "stocs/tracking/segment_follower.h"

#include <algorithm>
#include <cmath>

#include "stocs/estimation/pipeline.h"
#include "stocs/estimation/stages/free_space_check.h"
#include "stocs/estimation/stages/least_constrained_slide.h"
#include "stocs/estimation/stages/pose_covariance.h"

namespace stocs {
namespace {

/// At most this share of a hidden pose's seen samples may lie where the sensor sees through: about
/// what accepted follows show (1.4% in median, 7% at the 90th percentile on the tuning sequence).
constexpr float kHiddenFreeSpace = 0.05f;
/// At least this share of a hidden pose's seen samples lie behind a nearer measured surface.
constexpr float kHiddenShare = 0.5f;

}  // namespace

cv::Rect predictedBox(const PoseProximity& extent, const Eigen::Isometry3f& pose,
                      const CameraIntrinsics& camera, float margin) {
  const cv::Rect image(0, 0, camera.width, camera.height);
  const Eigen::Vector3f c = pose * extent.centre();
  if (c.z() <= extent.radius()) return image;
  const Eigen::Vector2f uv = camera.project(c);
  // The sphere's image lies within radius * f / (z - radius) of its centre's projection.
  const double half = (1.0 + 2.0 * margin) * extent.radius() / (c.z() - extent.radius());
  const double half_u = half * camera.fx, half_v = half * camera.fy;
  const auto clampToInt = [](double x) { return static_cast<int>(std::clamp(x, -1e6, 1e6)); };
  const cv::Rect box(
      cv::Point(clampToInt(std::floor(uv.x() - half_u)), clampToInt(std::floor(uv.y() - half_v))),
      cv::Point(clampToInt(std::ceil(uv.x() + half_u)) + 1,
                clampToInt(std::ceil(uv.y() + half_v)) + 1));
  return box & image;
}

SegmentFollower::SegmentFollower(const ObjectInput& in, const cv::Rect& box) : in_(in) {
  const PipelineParams& params = *in.params;
  // One thread: a box holds a few thousand pixels, fewer than pay for waking a team (and on a
  // busy machine a team waiting for a core costs far more than the scan).
  segment_ = buildSoftSegment(*in.cloud, *in.probability, static_cast<float>(in.camera->fx),
                              params.segment, 1, box);
  scorer_.emplace(segment_, params.stocs.lcp);
  if (params.stocs.icp.enabled) icp_.emplace(segment_, params.stocs.icp);
}

InstancePose SegmentFollower::follow(const Eigen::Isometry3f& predicted) const {
  const ObjectModel& model = in_.model->model;
  const IcpRefiner* icp = icp_ ? &*icp_ : nullptr;
  InstancePose pose;
  const FreeSpaceCheck surface(*in_.cloud, *in_.camera, in_.params->stocs.free_space);
  pose.pose = icp ? icp->refine(model, predicted, -1, &*scorer_) : predicted;
  pose.covariance = poseCovariance(model, icp, pose.pose, -1, &*scorer_);
  if (icp) {  // without ICP the covariance is the prior's: no direction is known to be loose
    const Eigen::Isometry3f slid =
        slideAlongLeastConstrained(model, pose.pose, pose.covariance, *scorer_, surface);
    if (!slid.isApprox(pose.pose)) {
      pose.pose = slid;
      pose.covariance = poseCovariance(model, icp, pose.pose, -1, &*scorer_);
    }
  }
  pose.refined = !pose.pose.isApprox(predicted);
  pose.lcp = scorer_->detail(model, pose.pose, -1);
  pose.score = pose.lcp.score;
  judgeInstance(pose, model, &surface, *in_.probability, in_.params->confidence);
  return pose;
}

bool SegmentFollower::hiddenBehindNearerSurface(const Eigen::Isometry3f& pose) const {
  const FreeSpaceCheck surface(*in_.cloud, *in_.camera, in_.params->stocs.free_space);
  const SurfaceComparison c = surface.compare(in_.model->model, pose);
  if (c.seen == 0) return false;  // out of view or unmeasured: nothing says it is behind anything
  const float seen = static_cast<float>(c.seen);
  const float behind = static_cast<float>(c.seen - c.free - c.confirmed) / seen;
  return behind >= kHiddenShare && static_cast<float>(c.free) / seen <= kHiddenFreeSpace;
}

PoseEstimate SegmentFollower::search() const {
  // The search is confined to the box around the lost pose: the segment is the box's, not the
  // frame's, so the per-segment step rather than the frame's entry point.
  return detectOnSegment(segment_, *in_.cloud, *in_.probability, *in_.model, *in_.params,
                         in_.camera, in_.colour);
}

}  // namespace stocs
