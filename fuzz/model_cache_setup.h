#pragma once
// The model and preparation parameters whose cache entries fuzz_model_cache feeds to ModelCache,
// shared with the corpus generator so the seed entries carry the key the fuzzer's cache expects.

#include <Eigen/Core>
#include <cstring>
#include <filesystem>
#include <string>

#include "../src/model/model_cache_format.h"
#include "stocs/io/ply_writer.h"
#include "stocs/model/model_cache.h"

namespace stocs::fuzz {

constexpr float kCacheModelUnitScale = 0.001f;  // the model file is in mm, like BOP models

/// Coarse sampling and few viewpoints keep the rebuild after each rejected entry fast.
inline ModelPreparationParams cacheFuzzParams() {
  ModelPreparationParams p;
  p.sampling.sampling_ratio = 0.15f;
  p.sampling.normal_neighbours = 8;
  p.sampling.orientation_viewpoints = 6;
  return p;
}

/// Writes the model file into `dir` and returns its path: a 60 x 40 x 30 mm box as 5 x 5 points on
/// each face, a point model. A mesh would be sampled densely (20000 points at least) on every
/// rebuild, which would take most of a fuzz run; the cache's parsers do not care which it is.
inline std::string writeCacheFuzzModel(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  const Eigen::Vector3f half(0.03f, 0.02f, 0.015f);
  MeshData points;
  for (int axis = 0; axis < 3; ++axis) {
    for (float side : {-1.0f, 1.0f}) {
      for (int i = 0; i < 5; ++i) {
        for (int j = 0; j < 5; ++j) {
          Eigen::Vector3f p;
          p[axis] = side * half[axis];
          p[(axis + 1) % 3] = (i / 2.0f - 1) * half[(axis + 1) % 3];
          p[(axis + 2) % 3] = (j / 2.0f - 1) * half[(axis + 2) % 3];
          points.vertices.push_back(p);
        }
      }
    }
  }
  const std::filesystem::path file = dir / "box.ply";
  writePly(file, points, 1000.0f);
  return file.string();
}

using detail::CacheEntryHeader;

/// The key of an entry, from its file name `<stem>-<key as 16 hex digits>.stocsmap`.
inline uint64_t entryKeyFromName(const std::filesystem::path& entry) {
  const std::string stem = entry.stem().string();
  return std::stoull(stem.substr(stem.rfind('-') + 1), nullptr, 16);
}

}  // namespace stocs::fuzz
