#pragma once
// What estimation needs besides sensor data: the configuration and the prepared model (samples,
// normals, PPF map) of every configured object. Immutable once loaded: a reload builds a new one
// and swaps it in, while estimations already running keep the one they started with; a runtime
// setting (dynamic_reconfigure) makes a copy with another configuration, sharing the models.

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "stocs/model/model_cache.h"
#include "stocs_ros/common/node_config.h"

namespace stocs_ros {

struct EstimationSetup {
  NodeConfig config;
  /// In config.objects order.
  std::vector<std::shared_ptr<const stocs::PreparedModel>> models;

  /// Reads `config_file` ($(dataset) in its paths standing for `dataset`) and builds or loads from
  /// the cache every model; `log` gets one line per model. Throws stocs::InputError for a bad
  /// config or model file.
  static std::shared_ptr<const EstimationSetup> load(
      const std::filesystem::path& config_file, const std::filesystem::path& dataset,
      const std::function<void(const std::string&)>& log);
};

}  // namespace stocs_ros
