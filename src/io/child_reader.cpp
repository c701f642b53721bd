#include "child_reader.h"

#include <dlfcn.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <link.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "mesh_reply.h"
#include "model_file_check.h"

extern char** environ;

namespace stocs::detail {
namespace {

constexpr int kReplyFd = 3;  // where stocs_mesh_reader writes its reply

/// How long the reader may take: a malformed file can make assimp work for minutes (a COLLADA
/// array declaring billions of values); a large mesh gets longer.
std::chrono::milliseconds readerDeadline(const std::string& path) {
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  const auto megabytes = ec ? 0 : static_cast<long>(bytes >> 20);
  return std::chrono::seconds(20) + std::chrono::seconds(1) * megabytes;
}

/// $STOCS_MESH_READER, else stocs_mesh_reader beside the shared library or program that holds
/// this function (the build puts and installs it there).
std::string meshReaderProgram() {
  if (const char* set = std::getenv("STOCS_MESH_READER")) return set;
  Dl_info info{};
  link_map* object = nullptr;
  std::filesystem::path holder = "/proc/self/exe";
  if (dladdr1(reinterpret_cast<void*>(&meshReaderProgram), &info, reinterpret_cast<void**>(&object),
              RTLD_DL_LINKMAP) != 0 &&
      object != nullptr && object->l_name != nullptr && object->l_name[0] != '\0') {
    holder = object->l_name;  // a shared library; the program itself has no name here
  }
  std::error_code ec;
  const std::filesystem::path resolved = std::filesystem::canonical(holder, ec);
  return ((ec ? holder : resolved).parent_path() / "stocs_mesh_reader").string();
}

/// Starts `program path ext` with the pipe's write end as its descriptor kReplyFd.
pid_t startReader(const std::string& program, const std::string& path, const std::string& ext,
                  int reply_fd, int& error) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, reply_fd, kReplyFd);
  std::vector<std::string> args = {program, path, ext};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  error = posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return error == 0 ? pid : -1;
}

/// Everything written to `fd` until its writer closes it; false when `deadline` passed first.
bool readAll(int fd, std::chrono::milliseconds deadline, std::vector<char>& out) {
  const auto end = std::chrono::steady_clock::now() + deadline;
  char buffer[65536];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        end - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    pollfd p{fd, POLLIN, 0};
    const int ready = poll(&p, 1, static_cast<int>(left.count()));
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) return false;
    const ssize_t n = read(fd, buffer, sizeof(buffer));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return true;
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

/// How the reader ended, for the error when it sent no complete reply.
std::string describeEnd(int status) {
  if (status != -1 && WIFSIGNALED(status)) {
    return fmt::format("crashed (signal {}: {})", WTERMSIG(status), strsignal(WTERMSIG(status)));
  }
  if (status != -1 && WIFEXITED(status)) {
    return fmt::format("failed (exit code {})", WEXITSTATUS(status));
  }
  return "failed (its end was not seen)";
}

/// The mesh or error the reader sent; throws InputError for an error or an incomplete reply.
MeshData parseReply(const std::string& path, const std::vector<char>& reply, int status) {
  const bool exited_ok = status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  MeshData mesh;
  if (exited_ok && !reply.empty()) {
    const std::vector<char> body(reply.begin() + 1, reply.end());
    if (reply[0] == static_cast<char>(MeshReply::kInputError)) {
      throw InputError(std::string(body.begin(), body.end()));
    }
    if (reply[0] == static_cast<char>(MeshReply::kMesh) && decodeMesh(body, mesh)) return mesh;
  }
  throw modelError(path, "the mesh reader " + describeEnd(status) + " reading this file");
}

}  // namespace

MeshData readAssimpModelInChild(const std::string& path, const std::string& ext) {
  const std::string program = meshReaderProgram();
  int fds[2];
  // Close-on-exec: a program another thread starts meanwhile must not hold the write end open
  // (the reader's copy, dup2'd to kReplyFd, has no close-on-exec; glibc clears it also when the
  // pipe's end already is kReplyFd).
  if (pipe2(fds, O_CLOEXEC) != 0) {
    throw modelError(path, fmt::format("cannot start the mesh reader: {}", strerror(errno)));
  }
  int error = 0;
  const pid_t pid = startReader(program, path, ext, fds[1], error);
  close(fds[1]);
  if (pid < 0) {
    close(fds[0]);
    throw modelError(path, fmt::format("cannot start the mesh reader {}: {} (STOCS_MESH_READER "
                                       "names it when it is elsewhere)",
                                       program, strerror(error)));
  }
  // Read before waiting: a large mesh fills the pipe, and the reader waits for it to drain.
  std::vector<char> reply;
  const std::chrono::milliseconds deadline = readerDeadline(path);
  const bool ended = readAll(fds[0], deadline, reply);
  close(fds[0]);
  if (!ended) {
    kill(pid, SIGKILL);
    waitFor(pid);
    throw modelError(path, fmt::format("the mesh reader took more than {} s reading this file",
                                       deadline.count() / 1000));
  }
  return parseReply(path, reply, waitFor(pid));
}

}  // namespace stocs::detail
