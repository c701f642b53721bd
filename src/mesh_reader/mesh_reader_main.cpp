// stocs_mesh_reader PATH EXT: reads the mesh file at PATH (EXT its lower-case extension) with
// assimp and writes the reply (src/io/mesh_reply.h) to file descriptor 3. The core starts it
// (src/io/child_reader.cpp) so that a crash inside assimp ends this process, not the node or
// command that asked for the model. Exit code 0 when the reply was written, 1 otherwise, 2 for
// wrong arguments.
#include "assimp_model.h"
#include "mesh_reply.h"
#include "stocs/util/error.h"

int main(int argc, char** argv) {
  constexpr int kReplyFd = 3;
  if (argc != 3) return 2;
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
