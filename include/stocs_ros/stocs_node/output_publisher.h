#pragma once
// Publishes a frame's result: TF from the cloud's frame to <frame_prefix><object> (and
// <frame_prefix><object>_<k> for further instances, see instanceName), ~poses
// (PoseArray), ~objects (ObjectPoseArray) and ~markers (MarkerArray), as the config's output
// section selects, and ~pose/<object> (and ~pose/<object>_<k>; PoseWithCovarianceStamped), each
// advertised with its first pose and published only while subscribed. Rejected poses (low
// confidence) appear only in ~objects' `rejected`. A result older than one already published (a
// service call on explicit, older inputs) is not published: consumers see stamps that never go
// back, except when time itself went back (a bag loop, a restarted driver): results of the new
// timeline are published from its start, and those of earlier timelines no more. Called from one
// thread at a time (the estimation worker).

#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include <map>
#include <optional>
#include <set>
#include <string>

#include "stocs_ros/stocs_node/estimation_setup.h"
#include "stocs_ros/stocs_node/frame_estimation.h"
#include "stocs_ros/stocs_node/result_messages.h"

namespace stocs_ros {

class OutputPublisher {
 public:
  /// Advertises ~poses, ~objects and ~markers on `pnh`.
  explicit OutputPublisher(ros::NodeHandle& pnh);

  /// `timeline`: how often time had gone back when the result's frame was matched.
  void publish(const FrameResult& result, const EstimationSetup& setup, uint64_t timeline);

 private:
  void publishTransforms(const FrameResult& result, const EstimationSetup& setup);
  void publishPerObject(const FrameResult& result, const EstimationSetup& setup);

  ros::NodeHandle pnh_;
  ros::Publisher poses_;
  ros::Publisher objects_;
  ros::Publisher markers_;
  tf2_ros::TransformBroadcaster tf_;
  /// Last stamp sent per child frame: tf2 warns (TF_REPEATED_DATA) about a transform sent twice
  /// for one stamp, as happens when ~estimate runs again on a frame already estimated.
  std::map<std::string, ros::Time> tf_stamps_;
  std::set<MarkerKey> shown_markers_;
  std::map<std::string, ros::Publisher> per_object_;  ///< by instanceName
  std::optional<ros::Time> newest_stamp_;
  uint64_t timeline_ = 0;
};

}  // namespace stocs_ros
