#pragma once
// main() of the node executables: a bad configuration ends the process with exit code 1 and a
// message naming the problem, instead of an uncaught exception. SIGINT and SIGTERM are handled
// here rather than by roscpp, so that the node is destroyed while ROS still runs: what it logs on
// the way out (the StoCS node's final counts) is printed and sent to /rosout, which roscpp's own
// handler would have shut down first.

#include <ros/callback_queue.h>
#include <ros/ros.h>

#include <csignal>

#include "stocs/util/error.h"

namespace stocs_ros {

namespace detail {
inline volatile std::sig_atomic_t g_stop_requested = 0;
inline void requestStop(int) {
  g_stop_requested = 1;
}
}  // namespace detail

/// Constructs `Node` on the private node handle and serves the global callback queue until a
/// signal or a shutdown request (e.g. `rosnode kill`), then destroys the node and shuts ROS down.
template <class Node>
int runNode(int argc, char** argv, const char* name) {
  ros::init(argc, argv, name, ros::init_options::NoSigintHandler);
  std::signal(SIGINT, detail::requestStop);
  std::signal(SIGTERM, detail::requestStop);
  // Held outside the try: when the last handle goes, roscpp shuts down, console output included,
  // and the error below would never be printed.
  const ros::NodeHandle pnh("~");
  try {
    Node node{pnh};
    while (ros::ok() && !detail::g_stop_requested) {
      ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.1));
    }
  } catch (const stocs::InputError& e) {
    ROS_FATAL("%s: %s", name, e.what());
    return 1;
  }
  ros::shutdown();
  return 0;
}

}  // namespace stocs_ros
