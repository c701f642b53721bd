#include "hard_segment.h"

#include <opencv2/imgproc.hpp>

namespace stocs {

cv::Mat hardProbability(const cv::Mat& probability, float threshold) {
  cv::Mat hard;
  cv::threshold(probability, hard, threshold, 1.0, cv::THRESH_BINARY);
  return hard;
}

SoftSegmentParams hardSegmentParams(SoftSegmentParams params) {
  // Any value in (0, 1) separates the 0 and 1 pixels of a hard probability image.
  params.min_probability = 0.5f;
  return params;
}

SoftSegment buildHardSegment(const ObjectInput& input, float threshold) {
  return buildSoftSegment(*input.cloud, hardProbability(*input.probability, threshold),
                          static_cast<float>(input.camera->fx),
                          hardSegmentParams(input.params->segment));
}

}  // namespace stocs
