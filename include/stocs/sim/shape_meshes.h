#pragma once
// Closed triangle meshes of simple solids, made by code, for the project's own object models
// (meshes/), generated scenes and tests. Metres; every triangle is wound counter-clockwise seen
// from outside the solid.

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <vector>

#include "stocs/geometry/mesh.h"

namespace stocs {

/// An axis-aligned box of `size` centred at the origin.
MeshData boxMesh(const Eigen::Vector3f& size);

/// The surface of revolution about z through the (r, z) profile points, `segments` around. A
/// profile point of radius 0 at either end becomes a single pole vertex, so a profile from the axis
/// back to the axis gives a closed mesh. Outward winding for a profile that goes up the outside
/// (and down any inside, e.g. the cavity of a mug).
MeshData latheMesh(const std::vector<Eigen::Vector2f>& profile, int segments);

/// A closed cylinder of `radius` from z = 0 to z = `height`.
MeshData cylinderMesh(float radius, float height, int segments);

/// A tube of radius `tube_radius` along the arc of radius `arc_radius` about the origin in the x-z
/// plane, from angle `from` to `to` (radians from +x towards +z), closed by flat end caps.
MeshData tubeArcMesh(float arc_radius, float tube_radius, float from, float to, int arc_segments,
                     int tube_segments);

/// A box of `size` centred at the origin whose faces are grids of squares about `cell` metres
/// across (vertices shared within a face only): fine enough to paint a print on.
MeshData gridBoxMesh(const Eigen::Vector3f& size, float cell);

/// RGBA, as MeshData::colours.
using VertexColour = Eigen::Matrix<uint8_t, 4, 1>;

/// `mesh` with vertices of its own for every triangle, each triangle coloured by `paint` at its
/// centroid: flat colours whose edges follow the triangles, a print on a finely divided mesh.
MeshData paintedMesh(const MeshData& mesh,
                     const std::function<VertexColour(const Eigen::Vector3f&)>& paint);

/// Adds `part`, moved by `pose`, to `mesh` as a separate shell.
void appendMesh(MeshData& mesh, const MeshData& part,
                const Eigen::Isometry3f& pose = Eigen::Isometry3f::Identity());

}  // namespace stocs
