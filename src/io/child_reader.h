#pragma once
// Reading a model file in a separate process: a reader library that crashes on a malformed file
// (Debian's assimp 5.2.5 reads address 0 in its COLLADA parser, fuzz/known_crashes) then ends that
// process, not the node or command that asked for the model. The process is a program of its own
// (stocs_mesh_reader, src/mesh_reader), started with posix_spawn: a forked copy of a
// multi-threaded process (the node's spinner threads, the tracking's detection thread) may only
// make async-signal-safe calls, and assimp allocates, throws and takes locks that another thread
// may have held at the fork.

#include <string>

#include "stocs/geometry/mesh.h"

namespace stocs::detail {

/// readAssimpModel(path, ext), run in stocs_mesh_reader: returns its mesh or rethrows its
/// InputError. A reader killed by a signal or exiting otherwise gives InputError "model <path>:
/// the mesh reader crashed (signal 11: Segmentation fault) reading this file" or "... failed (exit
/// code N) ...", one that takes longer than 20 s plus 1 s per megabyte of the file is killed:
/// "... the mesh reader took more than N s reading this file"; one that cannot be started "model
/// <path>: cannot start the mesh reader <program>: <why>". The program is $STOCS_MESH_READER when
/// set, else stocs_mesh_reader in the folder of the library holding this code (the program's own
/// folder when the core is linked statically).
MeshData readAssimpModelInChild(const std::string& path, const std::string& ext);

}  // namespace stocs::detail
