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
  const uint64_t counts[3] = {mesh.vertices.size(), mesh.triangles.size(), mesh.colours.size()};
  return writeKind(fd, MeshReply::kMesh) && writeAll(fd, counts, sizeof(counts)) &&
         writeAll(fd, mesh.vertices.data(), mesh.vertices.size() * sizeof(Eigen::Vector3f)) &&
         writeAll(fd, mesh.triangles.data(), mesh.triangles.size() * sizeof(Eigen::Vector3i)) &&
         writeAll(fd, mesh.colours.data(), mesh.colours.size() * sizeof(mesh.colours[0]));
}

bool writeErrorReply(int fd, const std::string& message) {
  return writeKind(fd, MeshReply::kInputError) && writeAll(fd, message.data(), message.size());
}

bool decodeMesh(const std::vector<char>& body, MeshData& mesh) {
  uint64_t counts[3] = {0, 0, 0};
  if (body.size() < sizeof(counts)) return false;
  std::memcpy(counts, body.data(), sizeof(counts));
  const size_t sizes[3] = {sizeof(Eigen::Vector3f), sizeof(Eigen::Vector3i),
                           sizeof(mesh.colours[0])};
  // Counts from a reader that misbehaved: compared by division, as their products may overflow.
  size_t total = sizeof(counts);
  for (int k = 0; k < 3; ++k) {
    if (counts[k] > body.size() / sizes[k]) return false;
    total += counts[k] * sizes[k];
  }
  if (body.size() != total) return false;
  mesh.vertices.resize(counts[0]);
  mesh.triangles.resize(counts[1]);
  mesh.colours.resize(counts[2]);
  // Plain arrays of floats, ints and bytes, as the reader's vectors held them.
  const char* at = body.data() + sizeof(counts);
  void* arrays[3] = {mesh.vertices.data(), mesh.triangles.data(), mesh.colours.data()};
  for (int k = 0; k < 3; ++k) {
    if (counts[k] == 0) continue;  // an empty vector's data() may be null, not for memcpy
    std::memcpy(arrays[k], at, counts[k] * sizes[k]);
    at += counts[k] * sizes[k];
  }
  return true;
}

}  // namespace stocs::detail
