#pragma once
// Instance boundaries from the colour image, for a bin of identical objects packed side by side,
// which a network's map covers as one surface and whose depth shows no step between them: the
// gaps between them are thin dark lines (a morphological black-hat finds them) and the outlines
// of their faces colour edges (Canny). Those edges rarely close an object's outline against its
// surroundings (a bin's wall); the object's map does, so where it is low is boundary too. The map
// this gives has the format of a boundary network's (labelRegions); print on the objects adds
// boundaries inside them, which split no object when the print's lines do not cross it.

#include <opencv2/core/mat.hpp>

#include "stocs/util/param_set.h"

namespace stocs {

struct ColourBoundaryParams {
  /// Whether StoCS derives a boundary map from the colour image when the frame has a colour image
  /// and no boundary map of its own (detectObject), and searches for at least `min_instances`.
  bool enabled = true;
  /// Boundaries split a single object's print as well; they are what tells instances apart.
  int min_instances = 2;
  /// Dark lines narrower than this (pixels) are boundaries: the black-hat's disc.
  int line_width = 9;
  /// How much darker (grey levels of 255) than its surroundings a line must be.
  int line_contrast = 20;
  /// Canny's lower threshold on the colour gradient (the upper one is twice it).
  int edge_threshold = 50;
  /// Pixels whose probability of the object is below this are boundary: the map closes outlines.
  float min_probability = 0.5f;

  /// Key, range, unit and meaning of every field (docs/parameters.md).
  static const ParamSet<ColourBoundaryParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
  /// Whether a search for `instances` poses per object uses colour boundaries.
  bool appliesTo(int instances) const { return enabled && instances >= min_instances; }
};

/// The boundary map of `bgr` (CV_8UC3) for an object whose map is `probability` (CV_32FC1, its
/// size): CV_8UC1, 255 interior, 0 on a boundary. Throws InputError for other types or sizes.
cv::Mat colourBoundaryMap(const cv::Mat& bgr, const cv::Mat& probability,
                          const ColourBoundaryParams& params);

}  // namespace stocs
