#pragma once
// Which colours a surface has, without its brightness: a coarse histogram of chromaticity (r and g
// over r + g + b). Shading scales a colour's channels alike and leaves its chromaticity, so a
// model's vertex colours and the pixels of a region of the image that shows it fall in the same
// bins. Maps from depth alone (GeometricSegmenter) weigh each region by how well its colours meet
// an object's: depth alone cannot tell two objects of one size apart, their colours often can.

#include <array>
#include <vector>

#include "stocs/geometry/mesh.h"

namespace cv {
class Mat;
}

namespace stocs {

class ChromaticityHistogram {
 public:
  static constexpr int kBins = 8;  ///< per axis over [0, 1]

  /// Of a model's colours in [0, 1] (unknown and too dark ones skipped).
  static ChromaticityHistogram of(const std::vector<Colour>& colours);
  /// Of a model file's surface: 2000 samples spread by area for a mesh (its vertex colours
  /// interpolated), the points' colours for a point model; empty without colour.
  static ChromaticityHistogram of(const MeshData& mesh);
  /// Of the pixels of `bgr` (CV_8UC3) where `mask` (CV_8UC1, its size) is non-zero; clipped
  /// pixels (mesh.h's isClipped) skipped.
  static ChromaticityHistogram of(const cv::Mat& bgr, const cv::Mat& mask);

  /// Adds a colour in [0, 1], spread over the four nearest bins; one that carries no chromaticity
  /// (unknown or too dark) is skipped.
  void add(const Colour& rgb);
  /// Adds the colours of `other` (the histogram of two surfaces together).
  ChromaticityHistogram& operator+=(const ChromaticityHistogram& other);
  /// Colours counted.
  int samples() const { return samples_; }
  /// The share of `other`'s colours this one also holds (histogram intersection of the two
  /// normalised histograms), in [0, 1]; 0 when either is empty.
  float overlap(const ChromaticityHistogram& other) const;

 private:
  std::array<float, kBins * kBins> bins_{};
  int samples_ = 0;
};

}  // namespace stocs
