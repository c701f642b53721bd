#include "stocs/pipeline.h"

#include <chrono>

namespace stocs {

void PipelineParams::validate() const {
  segment.validate();
  model.validate();
  stocs.validate();
}

ObjectEstimate estimateObject(const OrganizedCloud& cloud, float focal_px,
                              const cv::Mat& probability, const PreparedModel& model,
                              const PipelineParams& params, const cv::Mat* boundary_map) {
  const auto start = std::chrono::steady_clock::now();
  SoftSegment segment = buildSoftSegment(cloud, probability, focal_px, params.segment);
  if (boundary_map) labelRegions(segment, *boundary_map, cloud.width, cloud.height);
  ObjectEstimate result;
  result.segment_points = segment.size();
  result.estimate = StocsEstimator(model, params.stocs).estimate(segment);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace stocs
