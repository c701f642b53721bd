#pragma once
// What the mesh reader (src/mesh_reader, started by child_reader.cpp) sends back through its pipe:
// one byte saying what follows, then the mesh as plain arrays (vertex, triangle and colour counts,
// their floats, ints and bytes) or the message of the reader's InputError.

#include <string>
#include <vector>

#include "stocs/geometry/mesh.h"

namespace stocs::detail {

enum class MeshReply : char { kMesh = 'M', kInputError = 'E' };

/// Writes the mesh reply to `fd`; false when a write failed.
bool writeMeshReply(int fd, const MeshData& mesh);
/// Writes the error reply with `message` to `fd`; false when a write failed.
bool writeErrorReply(int fd, const std::string& message);

/// The mesh a mesh reply's body (after its first byte) holds; false when its length does not
/// match its counts.
bool decodeMesh(const std::vector<char>& body, MeshData& mesh);

}  // namespace stocs::detail
