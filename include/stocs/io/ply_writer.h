#pragma once
// Writing meshes as ascii PLY files that the project's own loader (and any PLY reader) reads.

#include <filesystem>

#include "stocs/geometry/mesh.h"

namespace stocs {

/// Writes `mesh` with its coordinates multiplied by `scale` (1000 for BOP models in mm) and printed
/// with `decimals` digits after the point, its colours (red green blue alpha uchar) when it has
/// them, plus its faces when it has triangles. The text depends on the mesh only, so regenerating a
/// mesh made by code gives the same file. Throws InputError naming the file when it cannot be
/// written.
void writePly(const std::filesystem::path& file, const MeshData& mesh, float scale = 1.0f,
              int decimals = 6);

}  // namespace stocs
