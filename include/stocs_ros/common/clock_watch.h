#pragma once
// A warning while a node runs on simulated time (/use_sim_time true) and no /clock has come: ROS
// time then stays 0, ros::Timer never fires and nothing is published, without a word (issue 42: a
// bag launch's use_sim_time:=true stays on the parameter server of a long-running roscore, and the
// next playback published 0 frames). Checked on the wall clock, which runs regardless.

#include <ros/ros.h>

#include <string>

namespace stocs_ros {

/// The warning for a node `who` that has waited `waited` seconds of wall time: empty unless it is
/// on simulated time (`sim_time`), no clock has arrived (`clock_arrived`) and `waited` reaches
/// `patience`.
std::string missingClockWarning(const std::string& who, bool sim_time, bool clock_arrived,
                                double waited, double patience);

class ClockWatch {
 public:
  /// Every `patience` seconds of wall time, warns (ROS_WARN) while missingClockWarning says so;
  /// stops once ROS time runs. `who` names the node in the message.
  ClockWatch(ros::NodeHandle nh, std::string who, double patience = 5.0);

 private:
  void check(const ros::WallTimerEvent& event);

  std::string who_;
  double patience_;
  ros::WallTime started_;
  ros::WallTimer timer_;
};

}  // namespace stocs_ros
