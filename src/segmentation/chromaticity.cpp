#include "stocs/segmentation/chromaticity.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>

#include "stocs/geometry/surface_sampling.h"
#include "stocs/util/error.h"
#include "stocs/util/random.h"

namespace stocs {

ChromaticityHistogram ChromaticityHistogram::of(const std::vector<Colour>& colours) {
  ChromaticityHistogram h;
  for (const Colour& c : colours) h.add(c);
  return h;
}

ChromaticityHistogram ChromaticityHistogram::of(const MeshData& mesh) {
  if (!mesh.hasColour()) return {};
  if (!mesh.isMesh()) {
    std::vector<Colour> colours;
    for (const Rgba& c : mesh.colours) colours.push_back(toColour(c));
    return of(colours);
  }
  constexpr size_t kSamples = 2000;
  Rng rng(1);  // the same histogram for the same mesh
  return of(sampleMeshSurface(mesh, kSamples, rng).colours);
}

ChromaticityHistogram ChromaticityHistogram::of(const cv::Mat& bgr, const cv::Mat& mask) {
  if (bgr.type() != CV_8UC3 || mask.type() != CV_8UC1 || bgr.size() != mask.size()) {
    throw InputError("chromaticity: expected a BGR image (CV_8UC3) and a mask of its size");
  }
  ChromaticityHistogram h;
  for (int y = 0; y < bgr.rows; ++y) {
    const cv::Vec3b* row = bgr.ptr<cv::Vec3b>(y);
    const uchar* inside = mask.ptr<uchar>(y);
    for (int x = 0; x < bgr.cols; ++x) {
      if (!inside[x]) continue;
      const Colour observed = Colour(row[x][2], row[x][1], row[x][0]) / 255.0f;
      if (!isClipped(observed)) h.add(observed);
    }
  }
  return h;
}

void ChromaticityHistogram::add(const Colour& rgb) {
  if (!carriesChromaticity(rgb)) return;
  const float sum = rgb.sum();
  // Bin centres at (i + 0.5) / kBins: bilinear weights over the four nearest.
  const float u = std::clamp(rgb.x() / sum * kBins - 0.5f, 0.0f, kBins - 1.0f);
  const float v = std::clamp(rgb.y() / sum * kBins - 0.5f, 0.0f, kBins - 1.0f);
  const int u0 = std::min(static_cast<int>(u), kBins - 2),
            v0 = std::min(static_cast<int>(v), kBins - 2);
  const float fu = u - u0, fv = v - v0;
  bins_[v0 * kBins + u0] += (1 - fu) * (1 - fv);
  bins_[v0 * kBins + u0 + 1] += fu * (1 - fv);
  bins_[(v0 + 1) * kBins + u0] += (1 - fu) * fv;
  bins_[(v0 + 1) * kBins + u0 + 1] += fu * fv;
  ++samples_;
}

ChromaticityHistogram& ChromaticityHistogram::operator+=(const ChromaticityHistogram& other) {
  for (size_t i = 0; i < bins_.size(); ++i) bins_[i] += other.bins_[i];
  samples_ += other.samples_;
  return *this;
}

float ChromaticityHistogram::overlap(const ChromaticityHistogram& other) const {
  if (samples_ == 0 || other.samples_ == 0) return 0;
  float shared = 0;
  for (size_t i = 0; i < bins_.size(); ++i) {
    shared += std::min(bins_[i] / samples_, other.bins_[i] / other.samples_);
  }
  return shared;
}

}  // namespace stocs
