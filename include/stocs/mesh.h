#pragma once
// A model as read from disk: vertices (metres) and, for meshes, triangles.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace stocs {

struct MeshData {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;  // empty for a point model

  bool isMesh() const { return !triangles.empty(); }
};

/// Reads a PLY (ascii or binary; points only or polygon mesh, polygons fan-triangulated) or PCD
/// file and multiplies coordinates by `unit_scale` (0.001 for BOP models in mm). Throws InputError
/// naming the file for a missing, unreadable or malformed file, no vertices, non-finite
/// coordinates, a face index out of range, or a size that is implausible for a graspable object
/// (diameter outside 1 mm .. 10 m, usually a wrong unit scale).
MeshData loadMesh(const std::string& path, float unit_scale);

/// Largest distance between two points (exact on the extreme points along 256 directions, which
/// contain the diameter's endpoints up to a relative error below 1e-3).
float pointSetDiameter(const std::vector<Eigen::Vector3f>& points);

}  // namespace stocs
