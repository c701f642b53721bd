#pragma once
// The demo's listener: waits for `~frames` messages on `objects` (stocs_ros/ObjectPoseArray),
// prints each object's pose, score and the input-to-output latency, writes the last frame's poses
// as a BOP results file (`~results`, for `~scene` / `~image` of the played dataset) and shuts ROS
// down. After `~timeout` seconds without enough frames it shuts down without writing anything, so
// the demo fails.

#include <ros/ros.h>
#include <stocs_ros/ObjectPoseArray.h>

#include <string>
#include <vector>

#include "stocs_ros/demo_recorder/demo_recorder_params.h"

namespace stocs_ros {

class DemoRecorder {
 public:
  /// Throws stocs::InputError for a missing or out-of-range parameter.
  explicit DemoRecorder(const ros::NodeHandle& pnh);

 private:
  void onObjects(const ObjectPoseArray::ConstPtr& message);
  void writeResults(const ObjectPoseArray& message, double latency) const;

  ros::NodeHandle nh_;
  ros::Subscriber subscriber_;
  ros::WallTimer timeout_;
  DemoRecorderParams params_;
  std::vector<double> latencies_;
};

}  // namespace stocs_ros
