#pragma once
// The node's EstimationSetup: loaded from ~config at start, replaced by ~reload. Estimations hold
// the setup they started with, so a reload never changes one under way. Thread-safe.

#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include "stocs_ros/stocs_node/estimation_setup.h"

namespace stocs_ros {

class SetupStore {
 public:
  /// Reads the configuration file `config_file` ($(dataset) in its paths standing for `dataset`)
  /// and prepares its models. Throws stocs::InputError naming the problem.
  SetupStore(std::string config_file, std::string dataset);

  std::shared_ptr<const EstimationSetup> current() const;
  /// Reads the file again and swaps the new setup in; returns what was reloaded. Throws
  /// stocs::InputError, keeping the current setup, for a bad file or one whose object names or
  /// input section changed (the subscriptions are made for those).
  std::string reload();
  /// Swaps in a setup whose configuration is `change(current configuration)`, sharing the current
  /// models (runtime settings). What `change` throws leaves the setup as it was.
  void change(const std::function<NodeConfig(const NodeConfig&)>& change);
  const std::string& file() const { return config_file_; }

 private:
  std::shared_ptr<const EstimationSetup> load() const;

  const std::string config_file_;
  const std::string dataset_;  ///< what $(dataset) in the configuration's paths stands for
  mutable std::mutex mutex_;   // guards setup_
  std::shared_ptr<const EstimationSetup> setup_;
};

}  // namespace stocs_ros
