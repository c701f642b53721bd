// The StoCS node as a nodelet (see common/nodelet_of.h).
#include <pluginlib/class_list_macros.hpp>

#include "stocs_ros/common/nodelet_of.h"
#include "stocs_ros/stocs_node/stocs_node.h"

namespace stocs_ros {
class StocsNodelet : public NodeletOf<StocsNode> {};
}  // namespace stocs_ros

PLUGINLIB_EXPORT_CLASS(stocs_ros::StocsNodelet, nodelet::Nodelet)
