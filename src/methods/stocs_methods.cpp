// StoCS and its hard-segmentation ablation as PoseMethods.
#include "stocs/methods/stocs_methods.h"

#include "hard_segment.h"

namespace stocs {

PoseEstimate StocsMethod::estimate(const ObjectInput& in) {
  return detectObject(in);
}

PoseEstimate HardSegmentStocsMethod::estimate(const ObjectInput& in) {
  // StoCS without the soft prior: the segment the baselines see (see hard_segment.h).
  PipelineParams params = *in.params;
  params.segment = hardSegmentParams(params.segment);
  const cv::Mat probability = hardProbability(*in.probability, threshold_);
  ObjectInput hard = in;
  hard.params = &params;
  hard.probability = &probability;
  return detectObject(hard);
}

}  // namespace stocs
