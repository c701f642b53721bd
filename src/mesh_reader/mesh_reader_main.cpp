// stocs_mesh_reader PATH EXT: reads the mesh file at PATH (EXT its lower-case extension) with
// assimp and writes the reply (src/io/mesh_reply.h) to file descriptor 3. The core starts it
// (src/io/child_reader.cpp) so that a crash inside assimp ends this process, not the node or
// command that asked for the model. Exit code 0 when the reply was written, 1 otherwise, 2 for
// wrong arguments.
#include <sys/resource.h>

#include <filesystem>

#include "assimp_model.h"
#include "mesh_reply.h"
#include "stocs/util/error.h"

#if defined(__SANITIZE_ADDRESS__)
#define STOCS_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define STOCS_ADDRESS_SANITIZER 1
#endif
#endif

namespace {

/// A malformed file can make assimp ask for tens of gigabytes (a COLLADA array declaring billions
/// of values): the reader's address space is capped at 4 GiB and 32 times the file, so that the
/// request fails here instead of taking the machine's memory. Not under AddressSanitizer, whose
/// shadow memory alone is larger (the parent's deadline still ends such a reader).
void capMemory(const char* path) {
#ifndef STOCS_ADDRESS_SANITIZER
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  const rlim_t cap = (rlim_t{4} << 30) + 32 * static_cast<rlim_t>(ec ? 0 : bytes);
  const rlimit limit{cap, cap};
  setrlimit(RLIMIT_AS, &limit);
#else
  (void)path;
#endif
}

}  // namespace

int main(int argc, char** argv) {
  constexpr int kReplyFd = 3;
  if (argc != 3) return 2;
  capMemory(argv[1]);
  try {
    return stocs::detail::writeMeshReply(kReplyFd, stocs::detail::readAssimpModel(argv[1], argv[2]))
               ? 0
               : 1;
  } catch (const stocs::InputError& e) {
    return stocs::detail::writeErrorReply(kReplyFd, e.what()) ? 0 : 1;
  } catch (...) {  // std::bad_alloc and the like: reported as a failed reader
    return 1;
  }
}
