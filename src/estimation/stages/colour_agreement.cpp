#include "stocs/estimation/stages/colour_agreement.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <vector>

namespace stocs {
namespace {

Eigen::Vector3f chromaticity(const Eigen::Vector3f& rgb) {
  return rgb / rgb.sum();
}

/// The (model, observed) colour pairs of the pose's confirmed samples that carry chromaticity.
void collectPairs(const ObjectModel& model, const Eigen::Isometry3f& pose,
                  const FreeSpaceCheck& visibility, const cv::Mat& colour,
                  std::vector<Eigen::Vector3f>& model_rgb, std::vector<Eigen::Vector3f>& seen_rgb) {
  visibility.visit(model, pose, [&](size_t i, int u, int v, SampleView view) {
    const Colour& m = model.colours[i];
    if (view != SampleView::kConfirmed || !carriesChromaticity(m)) return;
    const cv::Vec3b& bgr = colour.at<cv::Vec3b>(v, u);
    const Eigen::Vector3f o = Eigen::Vector3f(bgr[2], bgr[1], bgr[0]) / 255.0f;
    if (!carriesChromaticity(o) || isClipped(o)) return;
    model_rgb.push_back(m);
    seen_rgb.push_back(o);
  });
}

}  // namespace

ColourAgreement colourAgreement(const ObjectModel& model, const Eigen::Isometry3f& pose,
                                const FreeSpaceCheck& visibility, const cv::Mat* colour) {
  ColourAgreement result;
  if (!model.hasColour() || !colour) return result;
  std::vector<Eigen::Vector3f> model_rgb, seen_rgb;
  model_rgb.reserve(model.size());
  seen_rgb.reserve(model.size());
  collectPairs(model, pose, visibility, *colour, model_rgb, seen_rgb);
  result.samples = static_cast<int>(model_rgb.size());
  if (result.samples < kMinColourSamples) return result;
  // Grey-world gain between the model's and the observed colours of these samples.
  Eigen::Vector3f model_sum = Eigen::Vector3f::Zero(), seen_sum = Eigen::Vector3f::Zero();
  for (size_t k = 0; k < model_rgb.size(); ++k) {
    model_sum += model_rgb[k];
    seen_sum += seen_rgb[k];
  }
  const Eigen::Vector3f gain = seen_sum.cwiseQuotient(model_sum.cwiseMax(1e-6f));
  const auto agreement = [&](const Eigen::Vector3f& model_colour, const Eigen::Vector3f& seen) {
    const Eigen::Vector3f lit = gain.cwiseProduct(model_colour);
    // 2, the largest distance, where the gain leaves the model colour black.
    const float distance =
        lit.sum() > 0 ? (chromaticity(lit) - chromaticity(seen)).lpNorm<1>() : 2.0f;
    return std::max(0.0f, 1 - distance / kChromaticityTolerance);
  };
  // A permutation keeps the channel sums, so the chance pairs share the gain.
  const size_t n = model_rgb.size();
  double total = 0, chance = 0, squares = 0;
  for (size_t k = 0; k < n; ++k) {
    const float placed = agreement(model_rgb[k], seen_rgb[k]);
    const float shuffled = agreement(model_rgb[(k + n / 2) % n], seen_rgb[k]);
    total += placed;
    chance += shuffled;
    squares += static_cast<double>(placed - shuffled) * (placed - shuffled);
  }
  result.evidence = true;
  result.agreement = static_cast<float>(total / result.samples);
  result.chance = static_cast<float>(chance / result.samples);
  const double mean = (total - chance) / result.samples;
  const double variance = std::max(0.0, squares / result.samples - mean * mean);
  result.chance_error = static_cast<float>(std::sqrt(variance / (result.samples - 1)));
  return result;
}

}  // namespace stocs
