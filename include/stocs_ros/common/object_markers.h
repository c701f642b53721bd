#pragma once
// rviz markers of an object model at a pose, shared by the node's ~markers (its estimates) and the
// scene publisher's ~ground_truth_markers (the truth), so that both draw the same thing: the
// object's mesh where its config names one, else its model samples as points. Also where a label
// sits on its object, and the deletion of markers no longer shown.

#include <std_msgs/ColorRGBA.h>
#include <visualization_msgs/MarkerArray.h>

#include <Eigen/Geometry>
#include <set>
#include <string>
#include <utility>

#include "stocs/model/object_model.h"
#include "stocs_ros/common/node_config.h"

namespace stocs_ros {

/// A marker's namespace and id.
using MarkerKey = std::pair<std::string, int>;

/// The body of an object at `pose` (model to marker frame): a MESH_RESOURCE of `config.mesh_url`
/// scaled by `config.mesh_scale`, or else up to 2000 of `model`'s samples as POINTS (`model` is
/// unused with a mesh). Namespace, id and header are the caller's.
visualization_msgs::Marker bodyMarker(const ObjectConfig& config, const stocs::ObjectModel& model,
                                      const Eigen::Isometry3d& pose,
                                      const std_msgs::ColorRGBA& colour);

/// Where a text label of height `text_height` sits on an object at `pose` in a camera optical frame
/// (y down), as the camera sees it: centred over the model's extent in the image, its lower edge a
/// quarter of its height above the model's top, at the depth of the model's middle; so labels of
/// neighbouring objects stay on their own object. The pose's origin when no sample is in front.
Eigen::Vector3d labelPositionAbove(const stocs::ObjectModel& model, const Eigen::Isometry3d& pose,
                                   double text_height);

/// Width of one character of an rviz text marker, in text heights (its font's are narrower).
constexpr double kLabelCharWidth = 0.5;

/// Moves text labels (TEXT_VIEW_FACING) up, as a camera at the frame's origin sees them, until no
/// two overlap: from the lowest label up, a label that overlaps one already placed goes just above
/// it (a fifth of its height apart). A label's box: its text height by kLabelCharWidth text
/// heights per character.
void separateOverlappingLabels(visualization_msgs::MarkerArray& markers);

/// Appends a DELETE marker for every key of `shown` (the previous call's) that `markers` does not
/// add now, then makes `shown` the keys `markers` adds.
void deleteMarkersNoLongerShown(visualization_msgs::MarkerArray& markers,
                                std::set<MarkerKey>& shown);

}  // namespace stocs_ros
