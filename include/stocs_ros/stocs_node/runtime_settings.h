#pragma once
// The node's settings that may change while it runs (the confidence threshold, the time budget,
// the tracking keys), served with dynamic_reconfigure's protocol (~set_parameters,
// ~parameter_descriptions, ~parameter_updates), so that rqt_reconfigure and dynparam change them.
// Each is described from the configuration's schema (meaning, range, default), so nothing is
// written twice. A change applies from the next frame and keeps every track; a value out of range
// is refused with the schema's message and the setting kept.

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <ros/ros.h>

#include <string>
#include <vector>

#include "stocs_ros/stocs_node/setup_store.h"

namespace stocs_ros {

/// The configuration keys settable at runtime.
const std::vector<std::string>& runtimeKeys();

/// dynamic_reconfigure's description of the runtime keys: one group per section ("estimation",
/// "tracking"), each parameter named by the key's last part, its type, meaning and range from
/// the schema, defaults from NodeConfig's.
dynamic_reconfigure::ConfigDescription describeRuntimeKeys();
/// The runtime keys' values in `config`.
dynamic_reconfigure::Config runtimeValues(const NodeConfig& config);
/// `config` with the values of `changes` (names as describeRuntimeKeys gives them; others are
/// refused). Throws stocs::InputError with the schema's message for a value out of range, an
/// unknown name or a wrong type.
NodeConfig withRuntimeValues(const NodeConfig& config, const dynamic_reconfigure::Config& changes);

class RuntimeSettings {
 public:
  /// Serves on `pnh`; `setups` must outlive it.
  RuntimeSettings(ros::NodeHandle& pnh, SetupStore& setups);
  /// Publishes the current values again (after ~reload).
  void publishValues();

 private:
  bool onSet(dynamic_reconfigure::Reconfigure::Request& request,
             dynamic_reconfigure::Reconfigure::Response& response);

  SetupStore& setups_;
  ros::Publisher descriptions_;
  ros::Publisher updates_;
  ros::ServiceServer service_;
};

}  // namespace stocs_ros
