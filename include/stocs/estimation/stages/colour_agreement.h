#pragma once
// Colour agreement of a pose hypothesis: how well the model's surface colour matches the colour
// image where the pose's surface is seen. Depth alone cannot tell near-symmetric poses apart (a box
// turned over, a can turned about its axis) when only the print differs (issue 43); colour can.
//
// The samples compared are those FreeSpaceCheck confirms: facing the camera and within its margin
// of the measured depth at their pixel, so occluders and background do not count. Lighting and
// white balance change observed colour by a gain per channel, so a diagonal gain is fitted per
// pose between the model's and the observed colours of those samples (grey-world: the ratio of
// their channel sums), and the gained model colour's chromaticity (r, g, b over their sum) is
// compared with the observed one. A sample's agreement falls linearly from 1 at equal
// chromaticities to 0 at kChromaticityTolerance (L1) apart; the pose's is their mean. Skipped:
// samples of unknown model colour, model colours too dark to carry chromaticity, and observed
// pixels too dark or saturated to carry it. Achromatic prints (black on white) do not count.
// Compare poses by it rather than thresholding it: on real images the truth's agreement stays well
// below 1, as the chromaticity of dark saturated colours is noisy (ycbv-0000 frames 3-5 with models
// coloured from frames 1-2: 0.24-0.51 at the truth, 0-0.23 at its half turns; RealColour test).

#include <Eigen/Geometry>
#include <cmath>

#include "stocs/estimation/stages/free_space_check.h"
#include "stocs/model/object_model.h"

namespace cv {
class Mat;
}

namespace stocs {

/// Fewer compared samples than this give no evidence.
constexpr int kMinColourSamples = 25;
/// Chromaticity distance (L1, of r, g, b over their sum) at which a sample counts as disagreeing.
constexpr float kChromaticityTolerance = 0.2f;

struct ColourAgreement {
  bool evidence = false;  ///< at least kMinColourSamples samples were compared
  float agreement = 0;    ///< in [0, 1], higher: the colours agree; 0 without evidence
  /// The agreement of the same pixels with the same model colours paired at random (each with the
  /// colour of the sample half the list away): what the colours give where they say nothing of
  /// the pose; equal to `agreement` on a face of one colour.
  float chance = 0;
  /// Standard error of agreement - chance (of the per-sample differences' mean).
  float chance_error = 0;
  int samples = 0;  ///< samples compared
};

/// What the colours say of the pose: its agreement above chance (the print in its place, not
/// merely colours the model has), where it differs from chance by two standard errors; else 0, as
/// without evidence (a face of a model coloured from frames that never saw it) or on a face of one
/// colour (a plain mug, where the noise of a few samples would pick a turn).
inline float colourEvidence(const ColourAgreement& a) {
  const float above = a.agreement - a.chance;
  return a.evidence && std::abs(above) >= 2 * a.chance_error ? above : 0.0f;
}

/// The colour agreement of `model` at `pose` (model to camera) with `colour` (CV_8UC3 BGR,
/// registered with the cloud of `visibility`); no evidence when the model has no colour or
/// `colour` is null. Cheap: one projection per sample.
ColourAgreement colourAgreement(const ObjectModel& model, const Eigen::Isometry3f& pose,
                                const FreeSpaceCheck& visibility, const cv::Mat* colour);

}  // namespace stocs
