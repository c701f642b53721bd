#pragma once
// The name of an object's pose as TF child frame (after a prefix) and label, shared by the node,
// the scene publisher (gt_<name>) and the demo recorder.

#include <string>

namespace stocs_ros {

/// "<object>" for instance 0, "<object>_<k>" for instance k > 0.
inline std::string instanceName(const std::string& object, size_t instance) {
  return instance == 0 ? object : object + "_" + std::to_string(instance);
}

}  // namespace stocs_ros
