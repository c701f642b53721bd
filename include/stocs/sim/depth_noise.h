#pragma once
// The errors of a structured-light or stereo depth camera (Kinect, RealSense), applied to a
// rendered depth image: axial noise that grows with depth squared (Nguyen et al., 3DIMPVT 2012),
// quantised disparity (a depth step that grows with depth squared), no depth on grazing surfaces
// and at depth edges, and random dropouts.

#include <cstdint>

#include <opencv2/core.hpp>

#include "stocs/geometry/camera.h"
#include "stocs/util/param_set.h"

namespace stocs {

struct DepthNoiseParams {
  /// Axial noise standard deviation sigma(z) = sigma_min + sigma_quadratic * (z - 0.4 m)^2, metres:
  /// 1.2 mm at 0.4 m, 3.1 mm at 1.4 m for a Kinect.
  float sigma_min = 0.0012f;
  float sigma_quadratic = 0.0019f;
  /// Depth step k z^2 (1/metres) from disparity quantisation: 1/8 pixel on a 580 px, 7.5 cm
  /// baseline camera gives 2.9 mm at 1 m. 0: no quantisation.
  float quantisation = 0.0029f;
  float edge_jump = 0.02f;         ///< metres between neighbours that makes a depth edge
  int edge_radius = 1;             ///< pixels around a depth edge that may lose their depth
  float edge_dropout = 0.6f;       ///< probability that a pixel at a depth edge has no depth
  float grazing_angle_deg = 78.f;  ///< surfaces seen at a larger angle to their normal: no depth
  float dropout = 0.002f;          ///< probability that any pixel has no depth

  /// These errors scaled by `level`: the noise and dropout probabilities multiplied (capped at 1),
  /// and at level 0 no error at all (no quantisation, no lost pixels).
  DepthNoiseParams atLevel(float level) const;
  /// Key, range, unit and meaning of every field.
  static const ParamSet<DepthNoiseParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
};

/// `depth` (CV_32FC1, metres, 0 = none) as the camera would measure it. `normals` (CV_32FC3, unit,
/// camera frame) give the viewing angle. Deterministic for a seed. Throws InputError on a type or
/// size mismatch.
cv::Mat applyDepthNoise(const cv::Mat& depth, const cv::Mat& normals,
                        const CameraIntrinsics& camera, const DepthNoiseParams& params,
                        uint64_t seed);

}  // namespace stocs
