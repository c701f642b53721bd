// The scene publisher as a nodelet (see common/nodelet_of.h).
#include <pluginlib/class_list_macros.hpp>

#include "stocs_ros/common/nodelet_of.h"
#include "stocs_ros/scene_publisher/scene_publisher.h"

namespace stocs_ros {
class ScenePublisherNodelet : public NodeletOf<ScenePublisher> {};
}  // namespace stocs_ros

PLUGINLIB_EXPORT_CLASS(stocs_ros::ScenePublisherNodelet, nodelet::Nodelet)
