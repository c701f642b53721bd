#include "stocs/segmentation/colour_boundaries.h"

#include <fmt/format.h>

#include <opencv2/imgproc.hpp>

#include "stocs/util/error.h"

namespace stocs {

const ParamSet<ColourBoundaryParams>& ColourBoundaryParams::schema() {
  using P = ColourBoundaryParams;
  static const ParamSet<P> schema =
      ParamSet<P>()
          .add(&P::enabled, "enabled",
               "derive instance boundaries from the colour image where a frame has none")
          .flag("--colour-boundaries")
          .add(&P::min_instances, "min_instances", "", ParamRange::closed(1, 100),
               "only when searching for at least this many instances per object")
          .add(&P::line_width, "line_width", "px", ParamRange::closed(3, 31),
               "dark lines narrower than this are boundaries (gaps between packed objects)")
          .add(&P::line_contrast, "line_contrast", "", ParamRange::closed(1, 255),
               "grey levels a line is darker than its surroundings")
          .add(&P::edge_threshold, "edge_threshold", "", ParamRange::closed(1, 1000),
               "Canny's lower threshold on the colour gradient (the upper is twice it)")
          .add(&P::min_probability, "min_probability", "", ParamRange::closed(0, 1),
               "pixels of a lower probability of the object are boundary (the map's outline)");
  return schema;
}

void ColourBoundaryParams::validate() const {
  schema().validate(*this);
}

cv::Mat colourBoundaryMap(const cv::Mat& bgr, const cv::Mat& probability,
                          const ColourBoundaryParams& params) {
  if (bgr.empty() || bgr.type() != CV_8UC3) {
    throw InputError(fmt::format("colour boundaries need an 8-bit BGR image, not type {}{}",
                                 bgr.type(), bgr.empty() ? " (empty)" : ""));
  }
  if (probability.type() != CV_32FC1 || probability.size() != bgr.size()) {
    throw InputError(
        fmt::format("colour boundaries: the probability map ({}x{}, type {}) must be "
                    "CV_32FC1 of the colour image's size ({}x{})",
                    probability.cols, probability.rows, probability.type(), bgr.cols, bgr.rows));
  }
  cv::Mat grey, dark_lines, edges;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  const cv::Mat disc =
      cv::getStructuringElement(cv::MORPH_ELLIPSE, {params.line_width, params.line_width});
  cv::morphologyEx(grey, dark_lines, cv::MORPH_BLACKHAT, disc);
  cv::Canny(bgr, edges, params.edge_threshold, 2.0 * params.edge_threshold);
  cv::Mat boundary = dark_lines > params.line_contrast;
  boundary |= edges;
  boundary |= probability < params.min_probability;
  cv::Mat interior;
  cv::bitwise_not(boundary, interior);
  return interior;
}

}  // namespace stocs
