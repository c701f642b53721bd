// The StoCS node as a nodelet, for zero-copy pipelines: same topics, services and behaviour.
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include <memory>

#include "stocs/error.h"
#include "stocs_ros/stocs_node.h"

namespace stocs_ros {

class StocsNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    try {
      node_ = std::make_unique<StocsNode>(getPrivateNodeHandle());
    } catch (const stocs::InputError& e) {
      NODELET_FATAL("stocs: %s", e.what());
      throw;
    }
  }

  std::unique_ptr<StocsNode> node_;
};

}  // namespace stocs_ros

PLUGINLIB_EXPORT_CLASS(stocs_ros::StocsNodelet, nodelet::Nodelet)
