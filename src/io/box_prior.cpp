// 2D boxes to a soft per-class prior (segmentation_inputs.h).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "stocs/io/segmentation_inputs.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

void checkBox(const BoxDetection& b, size_t index) {
  const cv::Rect2f& r = b.box;
  if (!(std::isfinite(r.x) && std::isfinite(r.y) && r.width > 0 && r.height > 0 &&
        std::isfinite(r.width) && std::isfinite(r.height))) {
    throw InputError(fmt::format(
        "box {} (class {}) is x {} y {} width {} height {}; it needs a finite corner and a "
        "positive finite size",
        index, b.class_id, r.x, r.y, r.width, r.height));
  }
  if (!(b.score >= 0.0f && b.score <= 1.0f)) {
    throw InputError(fmt::format("box {} (class {}) has score {}; it must be in [0, 1]", index,
                                 b.class_id, b.score));
  }
}

/// The prior's share of the score at `t`, the distance from the centre in half-sizes (0 .. 1).
float profile(float t, const SegmentationInputParams& params) {
  if (t <= params.box_core) return 1.0f;
  const float fall = (t - params.box_core) / (1.0f - params.box_core);
  return 1.0f - (1.0f - params.box_edge_level) * std::min(fall, 1.0f);
}

/// Draws one box's prior into `probability`, keeping the larger value where boxes overlap.
void drawBox(const BoxDetection& b, const SegmentationInputParams& params, cv::Mat& probability) {
  const cv::Rect2f& r = b.box;
  const float cx = r.x + 0.5f * r.width, cy = r.y + 0.5f * r.height;
  // Clamped as floats first: a box far outside the image must not overflow an int.
  const auto pixel = [](float x, int size) {
    return static_cast<int>(std::clamp(x, 0.0f, static_cast<float>(size)));
  };
  const int u0 = pixel(std::floor(r.x), probability.cols);
  const int v0 = pixel(std::floor(r.y), probability.rows);
  const int u1 = pixel(std::ceil(r.x + r.width), probability.cols);
  const int v1 = pixel(std::ceil(r.y + r.height), probability.rows);
  for (int v = v0; v < v1; ++v) {
    const float pv = profile(std::abs(v + 0.5f - cy) / (0.5f * r.height), params);
    float* row = probability.ptr<float>(v);
    for (int u = u0; u < u1; ++u) {
      const float pu = profile(std::abs(u + 0.5f - cx) / (0.5f * r.width), params);
      row[u] = std::max(row[u], b.score * std::min(pu, pv));
    }
  }
}

}  // namespace

cv::Mat boxProbability(const std::vector<BoxDetection>& boxes, int class_id, cv::Size size,
                       const SegmentationInputParams& params) {
  cv::Mat probability(size, CV_32F, cv::Scalar(0));
  for (size_t i = 0; i < boxes.size(); ++i) {
    checkBox(boxes[i], i);
    if (boxes[i].class_id == class_id) drawBox(boxes[i], params, probability);
  }
  return probability;
}

}  // namespace stocs
