#pragma once
// Reading object models from disk: PLY meshes and point sets, PCD point sets, and OBJ, STL, DAE,
// glTF and GLB meshes.

#include <string>

#include "stocs/geometry/mesh.h"

namespace stocs {

/// Reads a PLY (ascii or binary; points only or polygon mesh, polygons fan-triangulated) or PCD
/// file through PCL, or an OBJ (a missing .mtl is no error), STL (ascii or binary), COLLADA (.dae),
/// glTF or GLB file through assimp (every mesh of every node, placed by the node transforms, as
/// rviz places them: a COLLADA file's <unit> applies, its up axis does not), and multiplies
/// coordinates by `unit_scale` (0.001 for BOP models in mm). The model's frame is the file's own,
/// wherever its origin lies. Throws InputError naming the file for a missing, unreadable or
/// malformed file, no vertices, non-finite coordinates, a face index out of range, or a size that
/// is implausible for a graspable object (diameter outside 1 mm .. 10 m, usually a wrong unit
/// scale; the message names the unit the file is likely in).
MeshData loadMesh(const std::string& path, float unit_scale);

/// Whether `path`'s extension names a format of meshes only, read through assimp (OBJ, STL, DAE,
/// glTF, GLB): files rviz draws as a mesh marker in the frame loadMesh reads them in. PLY (which
/// may hold points only) and PCD are not.
bool isMeshOnlyFormat(const std::string& path);

}  // namespace stocs
