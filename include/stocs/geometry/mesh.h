#pragma once
// A model as read from disk (io/mesh_io.h): vertices (metres), for meshes triangles, and the
// surface's colour where the file carries it.

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace stocs {

/// A vertex colour: red, green, blue, alpha, 0-255.
using Rgba = Eigen::Matrix<uint8_t, 4, 1>;

struct MeshData {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;  // empty for a point model
  /// Colour of each vertex, RGBA 0-255, interpolated across triangles; alpha 0 marks a vertex of
  /// unknown colour (a point model coloured from images that never saw it). Empty: no colour.
  std::vector<Rgba> colours;

  bool isMesh() const { return !triangles.empty(); }
  bool hasColour() const { return !colours.empty(); }
};

/// A colour as the model samples hold it: RGB in [0, 1] (a file's 0-255 values / 255); NaN marks
/// an unknown colour.
using Colour = Eigen::Vector3f;

/// The colour of a sample whose surface colour is unknown.
inline Colour unknownColour() {
  return Colour::Constant(std::numeric_limits<float>::quiet_NaN());
}
inline bool isKnown(const Colour& c) {
  return !std::isnan(c.x());
}

/// Whether a colour's chromaticity (its channels over their sum) says more than noise: known and
/// not too dark (channels summing to at least 0.15 of 3).
inline bool carriesChromaticity(const Colour& c) {
  return c.sum() >= 0.15f;  // false for NaN
}
/// Whether a camera's colour is clipped (a channel at 250 of 255 or more): its chromaticity is
/// wrong. Model colours are what the surface is, so a full channel there is no clipping.
inline bool isClipped(const Colour& observed) {
  return observed.maxCoeff() >= 250.0f / 255.0f;
}

/// A vertex colour (RGBA 0-255, alpha 0 unknown) as a Colour.
inline Colour toColour(const Rgba& rgba) {
  return rgba[3] == 0 ? unknownColour() : Colour(rgba.head<3>().cast<float>() / 255.0f);
}

/// Largest distance between two points (exact on the extreme points along 256 directions, which
/// contain the diameter's endpoints up to a relative error below 1e-3).
float pointSetDiameter(const std::vector<Eigen::Vector3f>& points);

/// Smallest width of the points: the thinnest slab holding them, searched over 256 directions and
/// refined around the best (an upper bound, within about 1% of the exact one for a box). A set
/// inside another is never wider at its thinnest.
float pointSetMinWidth(const std::vector<Eigen::Vector3f>& points);

}  // namespace stocs
