#pragma once
// A frame's estimation result as ROS messages: the package's ObjectPoseArray, a PoseArray, and the
// rviz markers.

#include <geometry_msgs/PoseArray.h>
#include <stocs_ros/ObjectPoseArray.h>
#include <visualization_msgs/MarkerArray.h>

#include <set>
#include <string>

#include "stocs_ros/estimation_setup.h"
#include "stocs_ros/frame_estimation.h"

namespace stocs_ros {

/// The found objects, in the order of the result.
ObjectPoseArray toObjectPoseArray(const FrameResult& result, const EstimationSetup& setup);

/// The poses of the found objects, in the same order as toObjectPoseArray.
geometry_msgs::PoseArray toPoseArray(const FrameResult& result);

/// Per found object, its rviz mesh (config `mesh`) or else its model samples as points at its pose
/// and a text label "name score"; namespace = object name, ids 0 (body) and 1 (label). Objects in
/// `shown` (the names shown by the previous call) that are not found now get DELETE markers;
/// `shown` is updated.
visualization_msgs::MarkerArray toMarkers(const FrameResult& result, const EstimationSetup& setup,
                                          std::set<std::string>& shown);

}  // namespace stocs_ros
