#pragma once
// A program's node class as a nodelet: same topics, services, parameters and behaviour as the
// executable. In one manager, messages between nodelets pass as shared pointers, without
// serialization or a copy (launch/bop_playback.launch nodelet:=true; scripts/bench_latency.sh
// measures both ways).

#include <nodelet/nodelet.h>

#include <memory>

#include "stocs/util/error.h"

namespace stocs_ros {

/// A nodelet holding one `Node`, constructed on the nodelet's private handle; a bad configuration
/// is reported by name and fails the load, as it ends the executable.
template <class Node>
class NodeletOf : public nodelet::Nodelet {
 private:
  void onInit() override {
    try {
      node_ = std::make_unique<Node>(getPrivateNodeHandle());
    } catch (const stocs::InputError& e) {
      NODELET_FATAL("%s: %s", getName().c_str(), e.what());
      throw;
    }
  }

  std::unique_ptr<Node> node_;
};

}  // namespace stocs_ros
