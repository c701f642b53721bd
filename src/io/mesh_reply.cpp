#include "mesh_reply.h"

#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>

namespace stocs::detail {
namespace {

bool writeAll(int fd, const void* data, size_t size) {
  const char* bytes = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = write(fd, bytes, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    bytes += n;
    size -= static_cast<size_t>(n);
  }
  return true;
}

bool writeKind(int fd, MeshReply kind) {
  const char byte = static_cast<char>(kind);
  return writeAll(fd, &byte, 1);
}

}  // namespace

bool writeMeshReply(int fd, const MeshData& mesh) {
  const uint64_t counts[2] = {mesh.vertices.size(), mesh.triangles.size()};
  return writeKind(fd, MeshReply::kMesh) && writeAll(fd, counts, sizeof(counts)) &&
         writeAll(fd, mesh.vertices.data(), mesh.vertices.size() * sizeof(Eigen::Vector3f)) &&
         writeAll(fd, mesh.triangles.data(), mesh.triangles.size() * sizeof(Eigen::Vector3i));
}

bool writeErrorReply(int fd, const std::string& message) {
  return writeKind(fd, MeshReply::kInputError) && writeAll(fd, message.data(), message.size());
}

bool decodeMesh(const std::vector<char>& body, MeshData& mesh) {
  uint64_t counts[2] = {0, 0};
  if (body.size() < sizeof(counts)) return false;
  std::memcpy(counts, body.data(), sizeof(counts));
  // Counts from a reader that misbehaved: compared by division, as their products may overflow.
  if (counts[0] > body.size() / sizeof(Eigen::Vector3f) ||
      counts[1] > body.size() / sizeof(Eigen::Vector3i)) {
    return false;
  }
  const size_t vertex_bytes = counts[0] * sizeof(Eigen::Vector3f);
  if (body.size() != sizeof(counts) + vertex_bytes + counts[1] * sizeof(Eigen::Vector3i)) {
    return false;
  }
  mesh.vertices.resize(counts[0]);
  mesh.triangles.resize(counts[1]);
  // Plain arrays of floats and ints, as the reader's vectors held them.
  std::memcpy(static_cast<void*>(mesh.vertices.data()), body.data() + sizeof(counts), vertex_bytes);
  std::memcpy(static_cast<void*>(mesh.triangles.data()),
              body.data() + sizeof(counts) + vertex_bytes, counts[1] * sizeof(Eigen::Vector3i));
  return true;
}

}  // namespace stocs::detail
