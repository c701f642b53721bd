#pragma once
// Mesh formats read through assimp: OBJ, STL (ascii and binary), COLLADA (DAE), glTF and GLB.
// Only src/io includes assimp's headers.

#include <string>

#include "stocs/geometry/mesh.h"

namespace stocs::detail {

/// Whether `ext` (lower case, with its dot) names a format readAssimpModel reads.
bool isAssimpFormat(const std::string& ext);

/// The vertices (in the file's units) and triangles of every mesh of every node of the file at
/// `path` (`ext` its lower-case extension), each placed by its node's transform, the way rviz
/// places them: the root node's rotation is dropped (assimp's turn of a COLLADA Z_UP file to Y-up)
/// and its scale (a COLLADA <unit>) and translation kept. Polygons are triangulated; points and
/// lines add vertices only. Colours: assimp_colour.h (textured triangles are subdivided). Throws
/// InputError "model <path>: ..." for a file assimp cannot read, an incomplete scene or more
/// vertices than a model can hold.
MeshData readAssimpModel(const std::string& path, const std::string& ext);

}  // namespace stocs::detail
