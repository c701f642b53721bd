#pragma once
// Reading a model file in a child process: a reader library that crashes on a malformed file
// (Debian's assimp 5.2.5 reads address 0 in its COLLADA parser, fuzz/known_crashes) then ends the
// child, not the node or command that asked for the model.

#include <functional>
#include <string>

#include "stocs/geometry/mesh.h"

namespace stocs::detail {

/// Runs `read` in a forked child, which sends the mesh (or the message of its InputError) back
/// through a pipe and _exits, and returns that mesh or rethrows that InputError. A child killed by
/// a signal or exiting otherwise gives InputError "model <path>: the mesh reader crashed (signal
/// 11: Segmentation fault) reading this file" or "... failed (exit code N) ...". Safe in a
/// multi-threaded process: the child only runs `read` and writes to the pipe.
MeshData readInChildProcess(const std::string& path, const std::function<MeshData()>& read);

}  // namespace stocs::detail
