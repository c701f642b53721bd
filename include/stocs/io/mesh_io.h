#pragma once
// Reading object models from disk: PLY meshes and point sets, and PCD point sets.

#include <string>

#include "stocs/geometry/mesh.h"

namespace stocs {

/// Reads a PLY (ascii or binary; points only or polygon mesh, polygons fan-triangulated) or PCD
/// file and multiplies coordinates by `unit_scale` (0.001 for BOP models in mm). Throws InputError
/// naming the file for a missing, unreadable or malformed file, no vertices, non-finite
/// coordinates, a face index out of range, or a size that is implausible for a graspable object
/// (diameter outside 1 mm .. 10 m, usually a wrong unit scale).
MeshData loadMesh(const std::string& path, float unit_scale);

}  // namespace stocs
