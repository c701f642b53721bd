#pragma once
// The model and preparation parameters whose cache entries fuzz_model_cache feeds to ModelCache,
// shared with the corpus generator so the seed entries carry the key the fuzzer's cache expects.

#include <cstring>
#include <filesystem>
#include <string>

#include "../src/model/model_cache_format.h"
#include "stocs/io/ply_writer.h"
#include "stocs/model/model_cache.h"
#include "stocs/sim/shape_meshes.h"

namespace stocs::fuzz {

constexpr float kCacheModelUnitScale = 0.001f;  // the model file is in mm, like BOP models

/// Coarse sampling and few viewpoints keep the rebuild after each rejected entry fast.
inline ModelPreparationParams cacheFuzzParams() {
  ModelPreparationParams p;
  p.sampling.sampling_ratio = 0.5f;
  p.sampling.orientation_viewpoints = 6;
  return p;
}

/// Writes the model file (a 60 x 40 x 30 mm box) into `dir` and returns its path.
inline std::string writeCacheFuzzModel(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = dir / "box.ply";
  writePly(file, boxMesh({0.06f, 0.04f, 0.03f}), 1000.0f);
  return file.string();
}

using detail::CacheEntryHeader;

/// The key of an entry, from its file name `<stem>-<key as 16 hex digits>.stocsmap`.
inline uint64_t entryKeyFromName(const std::filesystem::path& entry) {
  const std::string stem = entry.stem().string();
  return std::stoull(stem.substr(stem.rfind('-') + 1), nullptr, 16);
}

}  // namespace stocs::fuzz
