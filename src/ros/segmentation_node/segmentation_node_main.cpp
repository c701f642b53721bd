// The segmentation node (see segmentation_node.h and docs/ros.md).
#include "stocs_ros/common/run_node.h"
#include "stocs_ros/segmentation_node/segmentation_node.h"

int main(int argc, char** argv) {
  return stocs_ros::runNode<stocs_ros::SegmentationNode>(argc, argv, "segmentation");
}
