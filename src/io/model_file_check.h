#pragma once
// Header checks run before PCL (or assimp, for GLB) parses a model file. PCL's PLY and PCD readers
// abort on asserts, dereference null or allocate whatever a header claims for some malformed
// headers (found by fuzz_ply_model and fuzz_pcd_model), so only headers of the shapes they handle
// reach them.

#include <string>

#include "stocs/util/error.h"

namespace stocs::detail {

/// The error for model file `path`: "model <path>: <why>".
InputError modelError(const std::string& path, const std::string& why);

/// Accepts `ply`, a `format` of ascii / binary_little_endian / binary_big_endian 1.0, comment and
/// obj_info lines, an `element vertex` (count >= 1) of scalar properties and an optional
/// `element face` with one list property `vertex_indices` (uchar count, int or uint indices); a
/// binary body must be long enough for the counts. Throws InputError "model <path>: ..." otherwise.
void checkPlyHeader(const std::string& path);

/// Accepts the PCD v0.7 header keywords (VERSION, FIELDS, SIZE, TYPE, COUNT, WIDTH, HEIGHT,
/// VIEWPOINT, POINTS, DATA), consistent field lists, WIDTH x HEIGHT == POINTS >= 1, DATA ascii /
/// binary / binary_compressed and a body long enough for POINTS. Throws InputError otherwise.
void checkPcdHeader(const std::string& path);

/// Accepts a binary glTF whose header (magic `glTF`, version 2) gives the file's own length and
/// whose chunks each fit in it. assimp allocates whatever the header and chunk lengths claim
/// (found by fuzz_mesh_model). Throws InputError otherwise.
void checkGlbChunks(const std::string& path);

}  // namespace stocs::detail
