// The StoCS pose estimation node (see stocs_node.h and docs/ros.md).
#include "stocs/util/openmp_wait.h"
#include "stocs_ros/common/run_node.h"
#include "stocs_ros/stocs_node/stocs_node.h"

int main(int argc, char** argv) {
  stocs::preferPassiveOpenMpWaiting(argv);
  return stocs_ros::runNode<stocs_ros::StocsNode>(argc, argv, "stocs");
}
