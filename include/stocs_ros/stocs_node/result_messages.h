#pragma once
// A frame's estimation result as ROS messages: the package's ObjectPoseArray, a PoseArray, and the
// rviz markers.

#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <stocs_ros/ObjectPoseArray.h>
#include <visualization_msgs/MarkerArray.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "stocs_ros/common/instance_name.h"
#include "stocs_ros/common/object_markers.h"
#include "stocs_ros/stocs_node/estimation_setup.h"
#include "stocs_ros/stocs_node/frame_estimation.h"

namespace stocs_ros {

/// One pose of a found object: its best pose (instance 0) or a further distinct instance
/// (estimation.stocs.instances > 1), with its score, confidence, covariance and acceptance.
struct FoundPose {
  const ObjectOutcome* outcome;
  size_t instance;
  stocs::InstancePose estimate;
};

/// Every accepted pose of the result: objects in result order, each object's instances best
/// first.
std::vector<FoundPose> foundPoses(const FrameResult& result);

/// Every rejected pose of the result, in the same order.
std::vector<FoundPose> rejectedPoses(const FrameResult& result);

/// Why `rejected` was rejected (stocs::InstancePose::rejection), or "rejected" where it says not.
std::string rejectionReason(const FoundPose& rejected);

/// The accepted poses (in the order of foundPoses, each covariance publishableCovariance) and the
/// rejected ones (rejectedPoses' order, with their reason).
ObjectPoseArray toObjectPoseArray(const FrameResult& result, const EstimationSetup& setup);

/// The accepted pose `found` with its publishable covariance, as the per-object topic sends it.
geometry_msgs::PoseWithCovarianceStamped toPoseWithCovariance(const FoundPose& found,
                                                              const FrameResult& result,
                                                              const EstimationSetup& setup);

/// The found poses, in the same order as toObjectPoseArray.
geometry_msgs::PoseArray toPoseArray(const FrameResult& result);

/// Per found pose, its body (bodyMarker: the config's mesh or else the model samples) in the
/// object's colour, and a white text label "instanceName confidence" (two decimals) above the
/// object (labelPositionAbove); namespace = object name, ids 2k (body) and 2k + 1 (label) for
/// instance k; and its uncertainty (uncertaintyMarker, at least kUncertaintyMinimumShare of the
/// model's diameter across, namespace kUncertaintyNamespace, id kUncertaintyIdsPerObject x object
/// index + k). Rejected poses get none.
/// Markers in `shown` (those of the previous call) that are not shown now get DELETE markers;
/// `shown` is updated.
inline const char* const kUncertaintyNamespace = "uncertainty";
/// Above the most instances per object (StocsParams::instances).
constexpr int kUncertaintyIdsPerObject = 1000;
/// The smallest diameter of the uncertainty ellipsoid, as a share of the object's diameter: one
/// object across, so that it shows around the opaque body it would otherwise hide in.
constexpr double kUncertaintyMinimumShare = 1.0;

visualization_msgs::MarkerArray toMarkers(const FrameResult& result, const EstimationSetup& setup,
                                          std::set<MarkerKey>& shown);

}  // namespace stocs_ros
