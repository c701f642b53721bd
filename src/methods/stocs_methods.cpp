// StoCS and its hard-segmentation ablation as PoseMethods.
#include <opencv2/imgproc.hpp>

#include "stocs/methods/stocs_methods.h"

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
  return fromObjectEstimate(
      estimateObject(*in.cloud, in.focal_px, *in.probability, *in.model, *in.params, in.boundary));
}

MethodResult HardSegmentStocsMethod::estimate(const MethodInput& in) {
  // The segment is the pixels above the threshold, all with the same weight: StoCS without the
  // soft prior, as the baselines see the scene.
  cv::Mat hard;
  cv::threshold(*in.probability, hard, threshold_, 1.0, cv::THRESH_BINARY);
  PipelineParams params = *in.params;
  params.segment.min_probability = 0.5f;
  return fromObjectEstimate(
      estimateObject(*in.cloud, in.focal_px, hard, *in.model, params, in.boundary));
}

}  // namespace stocs
