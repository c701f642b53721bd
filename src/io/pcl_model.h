#pragma once
// PLY and PCD models through PCL, after the header checks of model_file_check.h. PLY stays on PCL
// rather than assimp: assimp 5.2 refuses a PLY of points only ("Mesh contains no faces"), and with
// PCL the vertices, prepared models, cache entries and results stay as they were.

#include <string>

#include "stocs/geometry/mesh.h"

namespace stocs::detail {

/// The vertices (in the file's units) and triangles (polygons fan-triangulated) of the PLY or PCD
/// file `path`, `ext` its lower-case extension. Throws InputError "model <path>: ..." for a file
/// PCL cannot read, vertices without x, y, z, no vertices or a face index out of range.
MeshData readPclModel(const std::string& path, const std::string& ext);

}  // namespace stocs::detail
