// The StoCS node and the scene publisher as nodelets: same topics, services, parameters and
// behaviour as the executables. In one manager, the publisher's clouds and images reach the
// estimator as shared pointers, without serialization or a copy (launch/bop_playback.launch
// nodelet:=true; scripts/bench_latency.sh measures both ways).
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include <memory>

#include "stocs/util/error.h"
#include "stocs_ros/scene_publisher.h"
#include "stocs_ros/segmentation_node.h"
#include "stocs_ros/stocs_node.h"

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

class StocsNodelet : public NodeletOf<StocsNode> {};
class ScenePublisherNodelet : public NodeletOf<ScenePublisher> {};
class SegmentationNodelet : public NodeletOf<SegmentationNode> {};

}  // namespace stocs_ros

PLUGINLIB_EXPORT_CLASS(stocs_ros::StocsNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(stocs_ros::ScenePublisherNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(stocs_ros::SegmentationNodelet, nodelet::Nodelet)
