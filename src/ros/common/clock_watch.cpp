#include "stocs_ros/common/clock_watch.h"

#include <fmt/format.h>

#include <utility>

namespace stocs_ros {

std::string missingClockWarning(const std::string& who, bool sim_time, bool clock_arrived,
                                double waited, double patience) {
  if (!sim_time || clock_arrived || waited < patience) return {};
  return fmt::format(
      "{}: /use_sim_time is true but no /clock message has arrived in {:.0f} s: ROS time stays 0 "
      "and nothing runs. Play a bag with `rosbag play --clock`, or, if /use_sim_time was left "
      "true (a launch with use_sim_time:=true sets it on the master, where it stays), run "
      "`rosparam set /use_sim_time false` and restart the launch",
      who, waited);
}

ClockWatch::ClockWatch(ros::NodeHandle nh, std::string who, double patience)
    : who_(std::move(who)), patience_(patience), started_(ros::WallTime::now()) {
  // Nothing to watch on the wall clock; a wall timer, as a ros::Timer waits for the clock itself.
  if (!ros::Time::isSimTime()) return;
  timer_ = nh.createWallTimer(ros::WallDuration(patience_), &ClockWatch::check, this);
}

void ClockWatch::check(const ros::WallTimerEvent&) {
  const bool arrived = ros::Time::isValid();
  if (arrived) {
    timer_.stop();
    return;
  }
  const std::string warning = missingClockWarning(
      who_, ros::Time::isSimTime(), arrived, (ros::WallTime::now() - started_).toSec(), patience_);
  if (!warning.empty()) ROS_WARN("%s", warning.c_str());
}

}  // namespace stocs_ros
