// StoCS and its hard-segmentation ablation as PoseMethods.
#include "stocs/methods/stocs_methods.h"

#include "hard_segment.h"

namespace stocs {
namespace {

MethodResult fromObjectEstimate(const ObjectEstimate& e) {
  MethodResult r;
  r.found = e.estimate.found;
  r.pose = e.estimate.pose;
  r.score = e.estimate.lcp.score;
  for (const InstancePose& i : e.estimate.instances) r.instances.push_back({i.pose, i.lcp.score});
  r.segment_points = e.segment_points;
  r.hypotheses = e.estimate.hypotheses;
  r.seconds = e.seconds;
  return r;
}

}  // namespace

MethodResult StocsMethod::estimate(const MethodInput& in) {
  return fromObjectEstimate(estimateObject(*in.cloud, in.focal_px, *in.probability, *in.model,
                                           *in.params, in.boundary, in.camera));
}

MethodResult HardSegmentStocsMethod::estimate(const MethodInput& in) {
  // StoCS without the soft prior: the segment the baselines see (see hard_segment.h).
  PipelineParams params = *in.params;
  params.segment = hardSegmentParams(params.segment);
  return fromObjectEstimate(estimateObject(*in.cloud, in.focal_px,
                                           hardProbability(*in.probability, threshold_), *in.model,
                                           params, in.boundary, in.camera));
}

}  // namespace stocs
