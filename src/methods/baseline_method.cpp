#include "baseline_method.h"

#include <chrono>

#include "hard_segment.h"
#include "stocs/estimation/stages/icp_refiner.h"
#include "stocs/estimation/stages/lcp_scorer.h"

namespace stocs {
namespace {

/// StoCS's refinement rule (StocsEstimator): ICP from the pose, kept unless the alignment objective
/// drops below 90% of the unrefined pose's. A baseline's pose may score 0 (StoCS's never does), so
/// a refined pose must also score above 0: ICP from a pose far off can run away.
Eigen::Isometry3f refine(const ObjectModel& model, const SoftSegment& segment,
                         const Eigen::Isometry3f& pose, const StocsParams& params) {
  const Eigen::Isometry3f refined = refinePointToPlane(model, segment, pose, -1, params.icp);
  const LcpScorer scorer(segment, params.lcp);
  const float after = scorer.score(model, refined);
  return after > 0 && after >= 0.9f * scorer.score(model, pose) ? refined : pose;
}

}  // namespace

PoseEstimate BaselineMethod::estimate(const ObjectInput& in) {
  const auto start = std::chrono::steady_clock::now();
  in.params->validate();
  const SoftSegment segment = buildHardSegment(in, threshold_);
  PoseEstimate result;
  result.segment_points = segment.size();
  if (segment.size() >= kMinSegmentPoints) {
    const std::optional<BaselineHypothesis> h = search(segment, in);
    if (h && h->pose.matrix().allFinite()) {
      result.hypotheses = h->hypotheses;
      InstancePose only;
      only.score = static_cast<float>(h->score);
      only.pose = in.params->stocs.icp.enabled
                      ? refine(in.model->model, segment, h->pose, in.params->stocs)
                      : h->pose;
      result.instances.push_back(only);
    }
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace stocs
