#pragma once
// Preprocessed models (samples, normals, PPF map) cached on disk.
//
// An entry's name holds a 64-bit hash of the model file's bytes, the unit scale, every preparation
// parameter and the format version, so any change there selects a new entry. Inside, a header
// repeats that key and carries a checksum of the payload: a stale, truncated or corrupt entry is
// detected, reported and rebuilt, never trusted. Entries are written to a temporary file and
// renamed, so concurrent readers never see half a file.

#include <filesystem>
#include <optional>
#include <string>

#include "stocs/model/lathe_axis.h"
#include "stocs/model/near_symmetries.h"
#include "stocs/model/object_model.h"
#include "stocs/model/object_symmetries.h"
#include "stocs/model/ppf_hash_map.h"
#include "stocs/util/param_set.h"

namespace stocs {

struct ModelPreparationParams {
  ModelSamplingParams sampling;
  PpfParams ppf;

  /// Key, range, unit and meaning of every field (docs/parameters.md).
  static const ParamSet<ModelPreparationParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
};

struct PreparedModel {
  ObjectModel model;
  PpfHashMap ppf_map;
  /// findNearSymmetries(model): computed on loading, not stored in the cache.
  std::vector<NearSymmetry> near_symmetries;
  /// findShapeAlternatives(model): computed on loading, not stored in the cache.
  std::vector<ShapeAlternative> shape_alternatives;
  /// findLatheAxis(model, shape_alternatives): computed on loading, not stored in the cache.
  std::optional<LatheAxis> lathe;
  /// Declared by the user (the node's `symmetries`, models_info.json), not read from the model
  /// file: empty after loading.
  ObjectSymmetries symmetries;
};

/// Prepares a mesh or point model (metres) already in memory.
PreparedModel prepareMesh(const MeshData& mesh, const ModelPreparationParams& params);

/// Loads and prepares a model without any cache.
PreparedModel prepareModelFile(const std::string& model_file, float unit_scale,
                               const ModelPreparationParams& params);

enum class CacheOutcome {
  kLoaded,    ///< a valid entry was read
  kBuilt,     ///< no entry existed; built and stored
  kRebuilt,   ///< an entry existed but was invalid; rebuilt and replaced
  kUncached,  ///< cache disabled or not writable; built in memory only
};

struct CacheReport {
  CacheOutcome outcome = CacheOutcome::kUncached;
  std::string detail;           ///< why an entry was rebuilt or not stored
  std::filesystem::path entry;  ///< the entry file
};

const char* toString(CacheOutcome outcome);

class ModelCache {
 public:
  /// Bumped whenever the payload layout or the preparation algorithm changes.
  static constexpr uint32_t kFormatVersion = 3;  // 2: sample colours; 3: even_sampling

  /// A cache in `directory`; an empty path disables caching.
  explicit ModelCache(std::filesystem::path directory = defaultDirectory());

  /// $XDG_CACHE_HOME/stocs_ros, else $HOME/.cache/stocs_ros, else <temp>/stocs_ros-cache.
  static std::filesystem::path defaultDirectory();

  const std::filesystem::path& directory() const { return directory_; }

  /// The prepared model of `model_file`, from the cache when a valid entry exists. Throws
  /// InputError for a bad model file or parameters; cache problems never throw, they show in
  /// `report`.
  PreparedModel load(const std::string& model_file, float unit_scale,
                     const ModelPreparationParams& params, CacheReport* report = nullptr) const;

  /// Entry file for the given model bytes and parameters (exposed for tests).
  std::filesystem::path entryPath(const std::string& model_file, float unit_scale,
                                  const ModelPreparationParams& params) const;

 private:
  std::filesystem::path directory_;
};

}  // namespace stocs
