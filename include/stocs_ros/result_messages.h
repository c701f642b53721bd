#pragma once
// A frame's estimation result as ROS messages: the package's ObjectPoseArray, a PoseArray, and the
// rviz markers.

#include <geometry_msgs/PoseArray.h>
#include <stocs_ros/ObjectPoseArray.h>
#include <visualization_msgs/MarkerArray.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "stocs_ros/estimation_setup.h"
#include "stocs_ros/frame_estimation.h"
#include "stocs_ros/object_markers.h"

namespace stocs_ros {

/// One pose of a found object: its best pose (instance 0) or a further distinct instance
/// (estimation.stocs.instances > 1).
struct FoundPose {
  const ObjectOutcome* outcome;
  size_t instance;
  Eigen::Isometry3f pose;
  float score;
};

/// Every pose of the result: objects in result order, each object's instances best first.
std::vector<FoundPose> foundPoses(const FrameResult& result);

/// The name of an object's pose as TF child frame (after the prefix) and label: "<object>" for
/// instance 0, "<object>_<k>" for instance k > 0 (as the scene publisher names gt_<object>_<k>).
std::string instanceName(const std::string& object, size_t instance);

/// The found poses, in the order of foundPoses.
ObjectPoseArray toObjectPoseArray(const FrameResult& result, const EstimationSetup& setup);

/// The found poses, in the same order as toObjectPoseArray.
geometry_msgs::PoseArray toPoseArray(const FrameResult& result);

/// Per found pose, its body (bodyMarker: the config's mesh or else the model samples) in the
/// object's colour, and a white text label "instanceName score" above the object
/// (labelPositionAbove); namespace = object name, ids 2k (body) and 2k + 1 (label) for instance k.
/// Markers in `shown` (those of the previous call) that are not shown now get DELETE markers;
/// `shown` is updated.
visualization_msgs::MarkerArray toMarkers(const FrameResult& result, const EstimationSetup& setup,
                                          std::set<MarkerKey>& shown);

}  // namespace stocs_ros
