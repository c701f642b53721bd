// The segmentation node as a nodelet (see common/nodelet_of.h).
#include <pluginlib/class_list_macros.hpp>

#include "stocs_ros/common/nodelet_of.h"
#include "stocs_ros/segmentation_node/segmentation_node.h"

namespace stocs_ros {
class SegmentationNodelet : public NodeletOf<SegmentationNode> {};
}  // namespace stocs_ros

PLUGINLIB_EXPORT_CLASS(stocs_ros::SegmentationNodelet, nodelet::Nodelet)
