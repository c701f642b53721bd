#pragma once
// A model as read from disk (io/mesh_io.h): vertices (metres), for meshes triangles, and the
// surface's colour where the file carries it.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace stocs {

struct MeshData {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;  // empty for a point model
  /// Colour of each vertex, RGBA 0-255, interpolated across triangles; alpha 0 marks a vertex of
  /// unknown colour (a point model coloured from images that never saw it). Empty: no colour.
  std::vector<Eigen::Matrix<uint8_t, 4, 1>> colours;

  bool isMesh() const { return !triangles.empty(); }
  bool hasColour() const { return !colours.empty(); }
};

/// Largest distance between two points (exact on the extreme points along 256 directions, which
/// contain the diameter's endpoints up to a relative error below 1e-3).
float pointSetDiameter(const std::vector<Eigen::Vector3f>& points);

}  // namespace stocs
