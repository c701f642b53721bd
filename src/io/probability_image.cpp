#include "stocs/io/probability_image.h"

#include <fmt/format.h>

#include <cmath>
#include <opencv2/core.hpp>

#include "stocs/util/error.h"

namespace stocs {

cv::Mat toProbabilityImage(const cv::Mat& image, double uint16_scale) {
  if (image.empty()) throw InputError("probability image is empty");
  if (image.channels() != 1) {
    throw InputError(
        fmt::format("probability image has {} channels; expected 1", image.channels()));
  }
  double scale = 1.0;
  switch (image.depth()) {
    case CV_32F:
    case CV_64F:
      break;
    case CV_16U:
      if (!(uint16_scale > 0))
        throw InputError("probability scale for 16-bit images must be positive");
      scale = 1.0 / uint16_scale;
      break;
    case CV_8U:
      scale = 1.0 / 255.0;
      break;
    default:
      throw InputError(fmt::format(
          "probability image has OpenCV depth {}; expected 8U, 16U, 32F or 64F", image.depth()));
  }
  cv::Mat out;
  image.convertTo(out, CV_32F, scale);
  // Float maps may overshoot by rounding; integer maps are exact, so any value above the scale is
  // an encoding error.
  const float tolerance = image.depth() == CV_32F || image.depth() == CV_64F ? 1e-3f : 1e-6f;
  // The range test and the clamp are branch-free loops, vectorized at -O3 rather than a test and a
  // branch per pixel; a row that fails is scanned again for the message.
  const float lo = -tolerance, hi = 1.0f + tolerance;
  auto outside = [&](float p) {  // NaN is outside; no short-circuit, so the loop stays branch-free
    return static_cast<int>(!(p >= lo)) | static_cast<int>(!(p <= hi));
  };
  for (int v = 0; v < out.rows; ++v) {
    float* row = out.ptr<float>(v);
    int bad = 0;
    for (int u = 0; u < out.cols; ++u) bad |= outside(row[u]);
    if (bad) {
      for (int u = 0; u < out.cols; ++u) {
        const float p = row[u];
        if (outside(p)) {
          throw InputError(fmt::format(
              "probability image value {} at pixel (u={}, v={}) is outside [0, 1]{}", p, u, v,
              image.depth() == CV_16U ? fmt::format(" (raw value / {})", uint16_scale) : ""));
        }
      }
    }
    for (int u = 0; u < out.cols; ++u) {
      const float p = row[u] > 0.0f ? row[u] : 0.0f;
      row[u] = p < 1.0f ? p : 1.0f;
    }
  }
  return out;
}

}  // namespace stocs
