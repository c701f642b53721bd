// Plays a BOP dataset as ROS topics (see scene_publisher.h and docs/ros.md, "Scene publisher").
#include "stocs_ros/common/run_node.h"
#include "stocs_ros/scene_publisher/scene_publisher.h"

int main(int argc, char** argv) {
  return stocs_ros::runNode<stocs_ros::ScenePublisher>(argc, argv, "scene_publisher");
}
