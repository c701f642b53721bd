#pragma once
// main() of the node executables: a bad configuration ends the process with exit code 1 and a
// message naming the problem, instead of an uncaught exception.

#include <ros/ros.h>

#include "stocs/error.h"

namespace stocs_ros {

/// Constructs `Node` on the private node handle and spins until shutdown.
template <class Node>
int runNode(int argc, char** argv, const char* name) {
  ros::init(argc, argv, name);
  // Held outside the try: when the last handle goes, roscpp shuts down, console output included,
  // and the error below would never be printed.
  const ros::NodeHandle pnh("~");
  try {
    Node node{pnh};
    ros::spin();
  } catch (const stocs::InputError& e) {
    ROS_FATAL("%s: %s", name, e.what());
    return 1;
  }
  return 0;
}

}  // namespace stocs_ros
