// Labels and instance masks to soft per-class probability maps (segmentation_inputs.h).
#include <fmt/format.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "stocs/io/probability_image.h"
#include "stocs/io/segmentation_inputs.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

/// A hard mask (non-zero inside) as a soft map in [0, 1] of score 1: its border blurred, its
/// pixels at least at the inside floor.
cv::Mat softenMask(const cv::Mat& inside, const SegmentationInputParams& params) {
  cv::Mat soft;
  inside.convertTo(soft, CV_32F, 1.0 / 255.0);
  if (params.mask_border_px > 0) {
    cv::GaussianBlur(soft, soft, cv::Size(), params.mask_border_px, params.mask_border_px,
                     cv::BORDER_REPLICATE);
    // Where the blur took a thin part of the mask below the floor.
    cv::Mat(cv::max(soft, params.mask_inside_floor)).copyTo(soft, inside);
  }
  return soft;
}

void checkScore(float score, const std::string& what) {
  if (!(score >= 0.0f && score <= 1.0f)) {
    throw InputError(fmt::format("{} has score {}; it must be in [0, 1]", what, score));
  }
}

}  // namespace

cv::Mat labelProbability(const cv::Mat& labels, const cv::Mat& confidence, int class_id,
                         const SegmentationInputParams& params, double uint16_scale) {
  if (labels.empty()) throw InputError("label image is empty");
  if (labels.type() != CV_8UC1 && labels.type() != CV_16UC1) {
    throw InputError(fmt::format(
        "label image has OpenCV type {} with {} channels; expected one 8- or 16-bit channel "
        "(mono8, mono16) of class indices",
        labels.depth(), labels.channels()));
  }
  const cv::Mat inside = labels == class_id;
  cv::Mat probability = softenMask(inside, params);
  if (!confidence.empty()) {
    if (confidence.size() != labels.size()) {
      throw InputError(fmt::format("confidence image is {}x{} but the label image is {}x{}",
                                   confidence.cols, confidence.rows, labels.cols, labels.rows));
    }
    cv::Mat own;
    cv::multiply(probability, toProbabilityImage(confidence, uint16_scale), own);
    own.copyTo(probability, inside);  // the confidence is of the label's own class
  }
  return cv::max(probability, params.mask_outside_floor);
}

cv::Mat maskProbability(const std::vector<InstanceMask>& masks, int class_id, cv::Size size,
                        const SegmentationInputParams& params) {
  cv::Mat probability(size, CV_32F, cv::Scalar(params.mask_outside_floor));
  for (size_t i = 0; i < masks.size(); ++i) {
    const InstanceMask& m = masks[i];
    const std::string what = fmt::format("mask {} (class {})", i, m.class_id);
    checkScore(m.score, what);
    if (m.mask.type() != CV_8UC1) {
      throw InputError(fmt::format("{} has OpenCV type {}; expected one 8-bit channel (mono8)",
                                   what, m.mask.type()));
    }
    if (m.mask.size() != size) {
      throw InputError(fmt::format("{} is {}x{} but the depth image is {}x{}", what, m.mask.cols,
                                   m.mask.rows, size.width, size.height));
    }
    if (m.class_id != class_id) continue;
    cv::max(probability, softenMask(m.mask > 0, params) * m.score, probability);
  }
  return probability;
}

}  // namespace stocs
