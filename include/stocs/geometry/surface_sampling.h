#pragma once
// Even sampling of model surfaces: dense area-weighted samples of a mesh, thinned to a Poisson-disc
// set (no two samples closer than a radius, every input point within the radius of a sample).

#include <Eigen/Core>
#include <vector>

#include "stocs/geometry/mesh.h"
#include "stocs/util/random.h"

namespace stocs {

struct OrientedPoints {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> normals;
  std::vector<Colour> colours;  ///< empty when the source has no colour
};

/// Total triangle area of a mesh.
double meshArea(const MeshData& mesh);

/// `count` points uniformly distributed over the mesh surface by area, each with its triangle's
/// normal (following the winding order) and, when the mesh has vertex colours, the colour
/// interpolated between its corners' (mesh.h's Colour; unknown where unknown corners outweigh
/// known ones).
OrientedPoints sampleMeshSurface(const MeshData& mesh, size_t count, Rng& rng);

/// The colour at barycentric weights `w` of triangle `t`: known corners' colours weighted by `w`,
/// unknown when the known corners' weight is below one half.
Colour interpolateColour(const MeshData& mesh, const Eigen::Vector3i& t, const Eigen::Vector3f& w);

/// Greedy Poisson-disc thinning: visits points in a seeded random order and keeps a point when no
/// kept point lies within `radius`. Returns the kept indices in visiting order.
std::vector<size_t> poissonDiscSubset(const std::vector<Eigen::Vector3f>& points, float radius,
                                      Rng& rng);

}  // namespace stocs
