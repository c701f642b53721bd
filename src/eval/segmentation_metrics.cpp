#include "stocs/eval/segmentation_metrics.h"

#include <fmt/format.h>

#include <opencv2/core.hpp>

#include "stocs/util/error.h"

namespace stocs {

double PixelCounts::precision() const {
  const long segment = true_positive + false_positive;
  return segment == 0 ? 1.0 : static_cast<double>(true_positive) / segment;
}

double PixelCounts::recall() const {
  const long mask = true_positive + false_negative;
  return mask == 0 ? 1.0 : static_cast<double>(true_positive) / mask;
}

PixelCounts& PixelCounts::operator+=(const PixelCounts& other) {
  true_positive += other.true_positive;
  false_positive += other.false_positive;
  false_negative += other.false_negative;
  return *this;
}

PixelCounts countSegmentPixels(const cv::Mat& probability, const cv::Mat& mask, float threshold) {
  if (probability.type() != CV_32FC1 || mask.type() != CV_8UC1 ||
      probability.size() != mask.size()) {
    throw InputError(fmt::format(
        "segment counts need a CV_32FC1 probability map and a CV_8UC1 mask of one size; got {}x{} "
        "and {}x{}",
        probability.cols, probability.rows, mask.cols, mask.rows));
  }
  const cv::Mat segment = probability > threshold;
  const cv::Mat on_mask = mask != 0;
  PixelCounts c;
  c.true_positive = cv::countNonZero(segment & on_mask);
  c.false_positive = cv::countNonZero(segment & ~on_mask);
  c.false_negative = cv::countNonZero(~segment & on_mask);
  return c;
}

}  // namespace stocs
