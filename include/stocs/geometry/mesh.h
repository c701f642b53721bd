#pragma once
// A model as read from disk (io/mesh_io.h): vertices (metres) and, for meshes, triangles.

#include <Eigen/Core>
#include <vector>

namespace stocs {

struct MeshData {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;  // empty for a point model

  bool isMesh() const { return !triangles.empty(); }
};

/// Largest distance between two points (exact on the extreme points along 256 directions, which
/// contain the diameter's endpoints up to a relative error below 1e-3).
float pointSetDiameter(const std::vector<Eigen::Vector3f>& points);

}  // namespace stocs
