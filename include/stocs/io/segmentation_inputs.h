#pragma once
// Segmentation a robot already has, turned into the per-object probability maps StoCS takes: a
// semantic label image (class index per pixel, optional confidence), instance masks with a score
// each, and 2D boxes with a score each. Hard masks are softened (a blurred border and floors
// inside and outside), boxes become a soft prior that falls off toward their edges, so that the
// estimator keeps its tolerance to segmentation errors (docs/segmentation_inputs.md).

#include <vector>

#include <opencv2/core.hpp>

#include "stocs/util/param_set.h"

namespace stocs {

struct SegmentationInputParams {
  /// Pixels: standard deviation of the Gaussian that blurs a hard mask's border, so that the
  /// probability falls from the mask's score inside to the outside floor over about 2 of them on
  /// each side of the outline (where networks err most); 0: hard edges.
  float mask_border_px = 3.0f;
  /// A mask pixel keeps at least this share of its score after the blur (thin parts stay in the
  /// segment).
  float mask_inside_floor = 0.6f;
  /// Every pixel outside the masks of the object gets at least this probability (a missed part
  /// keeps some weight; below `estimation.segment.min_probability` it stays out of the segment).
  float mask_outside_floor = 0.0f;
  /// Share of a box's score left at its edge; the prior is the score at the box's centre part.
  float box_edge_level = 0.3f;
  /// Share of the box's half-width (half-height) around its centre where the prior is the full
  /// score; it falls linearly to `box_edge_level` times the score at the edge, and is 0 outside.
  float box_core = 0.5f;

  /// Key, range, unit and meaning of every field.
  static const ParamSet<SegmentationInputParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
};

/// One instance of an instance-segmentation network (Mask R-CNN, YOLO-seg).
struct InstanceMask {
  cv::Mat mask;  ///< CV_8UC1, non-zero inside, the depth image's size
  int class_id = 0;
  float score = 1.0f;  ///< in [0, 1]
};

/// One detection of a 2D detector.
struct BoxDetection {
  cv::Rect2f box;  ///< pixels: x, y of the top-left corner, width, height
  int class_id = 0;
  float score = 1.0f;  ///< in [0, 1]
};

/// The probability of class `class_id` from a label image (CV_8UC1 or CV_16UC1, class index per
/// pixel): its pixels softened as a mask of score 1, times `confidence` (empty, or any image
/// toProbabilityImage reads, the labels' size) on the class's own pixels. CV_32FC1 in [0, 1].
/// Throws InputError for another type, a multichannel image or a confidence of another size.
cv::Mat labelProbability(const cv::Mat& labels, const cv::Mat& confidence, int class_id,
                         const SegmentationInputParams& params, double uint16_scale = 10000.0);

/// The probability of class `class_id` over an image of `size`: each of its masks softened and
/// weighted by its score, the largest where they overlap. No mask of the class: the outside floor
/// everywhere. Throws InputError naming the mask (its index) of a wrong size or type, or a score
/// outside [0, 1].
cv::Mat maskProbability(const std::vector<InstanceMask>& masks, int class_id, cv::Size size,
                        const SegmentationInputParams& params);

/// The soft prior of class `class_id` over an image of `size` from its boxes (the largest where
/// they overlap; parts outside the image are cut). Throws InputError naming the box (its index)
/// with a non-finite or non-positive size, or a score outside [0, 1].
cv::Mat boxProbability(const std::vector<BoxDetection>& boxes, int class_id, cv::Size size,
                       const SegmentationInputParams& params);

}  // namespace stocs
