#include "child_reader.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <vector>

#include "model_file_check.h"

namespace stocs::detail {
namespace {

// The first byte the child sends: what follows it.
enum class Reply : char { kMesh = 'M', kInputError = 'E' };

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

/// The mesh as plain arrays: vertex and triangle counts, then their floats and ints.
bool sendMesh(int fd, const MeshData& mesh) {
  const uint64_t counts[2] = {mesh.vertices.size(), mesh.triangles.size()};
  return writeAll(fd, counts, sizeof(counts)) &&
         writeAll(fd, mesh.vertices.data(), mesh.vertices.size() * sizeof(Eigen::Vector3f)) &&
         writeAll(fd, mesh.triangles.data(), mesh.triangles.size() * sizeof(Eigen::Vector3i));
}

/// The child's whole life: no return, no exit handlers, no flushing of the parent's buffers.
[[noreturn]] void runChild(int fd, const std::function<MeshData()>& read) {
  bool sent = false;
  try {
    const MeshData mesh = read();
    const char reply = static_cast<char>(Reply::kMesh);
    sent = writeAll(fd, &reply, 1) && sendMesh(fd, mesh);
  } catch (const InputError& e) {
    const char reply = static_cast<char>(Reply::kInputError);
    sent = writeAll(fd, &reply, 1) && writeAll(fd, e.what(), std::strlen(e.what()));
  } catch (...) {  // std::bad_alloc and the like: reported as a failed reader
  }
  _exit(sent ? 0 : 1);
}

std::vector<char> readAll(int fd) {
  std::vector<char> out;
  char buffer[65536];
  for (;;) {
    const ssize_t n = read(fd, buffer, sizeof(buffer));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return out;
    out.insert(out.end(), buffer, buffer + n);
  }
}

int waitFor(pid_t pid) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return status;
}

/// How the child ended, for the error when it sent no complete reply.
std::string describeEnd(int status) {
  if (status != -1 && WIFSIGNALED(status)) {
    return fmt::format("crashed (signal {}: {})", WTERMSIG(status), strsignal(WTERMSIG(status)));
  }
  if (status != -1 && WIFEXITED(status)) {
    return fmt::format("failed (exit code {})", WEXITSTATUS(status));
  }
  return "failed (its end was not seen)";
}

/// The mesh sendMesh wrote into `bytes`; false when their length does not match its counts.
bool decodeMesh(const std::vector<char>& bytes, MeshData& mesh) {
  uint64_t counts[2] = {0, 0};
  if (bytes.size() < sizeof(counts)) return false;
  std::memcpy(counts, bytes.data(), sizeof(counts));
  const size_t vertex_bytes = counts[0] * sizeof(Eigen::Vector3f);
  if (bytes.size() != sizeof(counts) + vertex_bytes + counts[1] * sizeof(Eigen::Vector3i)) {
    return false;
  }
  mesh.vertices.resize(counts[0]);
  mesh.triangles.resize(counts[1]);
  // Plain arrays of floats and ints, as the child's vectors held them.
  std::memcpy(static_cast<void*>(mesh.vertices.data()), bytes.data() + sizeof(counts),
              vertex_bytes);
  std::memcpy(static_cast<void*>(mesh.triangles.data()),
              bytes.data() + sizeof(counts) + vertex_bytes, counts[1] * sizeof(Eigen::Vector3i));
  return true;
}

/// The mesh or error the child sent; throws InputError for an error or an incomplete reply.
MeshData parseReply(const std::string& path, const std::vector<char>& reply, int status) {
  const bool exited_ok = status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  MeshData mesh;
  if (exited_ok && !reply.empty()) {
    const std::vector<char> body(reply.begin() + 1, reply.end());
    if (reply[0] == static_cast<char>(Reply::kInputError)) {
      throw InputError(std::string(body.begin(), body.end()));
    }
    if (reply[0] == static_cast<char>(Reply::kMesh) && decodeMesh(body, mesh)) return mesh;
  }
  throw modelError(path, "the mesh reader " + describeEnd(status) + " reading this file");
}

}  // namespace

MeshData readInChildProcess(const std::string& path, const std::function<MeshData()>& read) {
  int fds[2];
  // Close-on-exec: a program another thread starts meanwhile must not hold the write end open.
  if (pipe2(fds, O_CLOEXEC) != 0) {
    throw modelError(path, fmt::format("cannot start the mesh reader: {}", strerror(errno)));
  }
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    runChild(fds[1], read);
  }
  close(fds[1]);
  if (pid < 0) {
    close(fds[0]);
    throw modelError(path, fmt::format("cannot start the mesh reader: {}", strerror(errno)));
  }
  // Read before waiting: a large mesh fills the pipe, and the child waits for it to drain.
  const std::vector<char> reply = readAll(fds[0]);
  close(fds[0]);
  return parseReply(path, reply, waitFor(pid));
}

}  // namespace stocs::detail
