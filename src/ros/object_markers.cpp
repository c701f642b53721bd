#include "stocs_ros/object_markers.h"

#include <tf2_eigen/tf2_eigen.h>

#include <algorithm>
#include <limits>

namespace stocs_ros {
namespace {

/// Enough points to show the shape; rviz slows down with whole models of many objects.
constexpr size_t kMaxMarkerPoints = 2000;

}  // namespace

visualization_msgs::Marker bodyMarker(const ObjectConfig& config, const stocs::ObjectModel& model,
                                      const Eigen::Isometry3d& pose,
                                      const std_msgs::ColorRGBA& colour) {
  visualization_msgs::Marker m;
  m.action = visualization_msgs::Marker::ADD;
  m.pose = tf2::toMsg(pose);
  m.color = colour;
  if (!config.mesh_url.empty()) {
    m.type = visualization_msgs::Marker::MESH_RESOURCE;
    m.mesh_resource = config.mesh_url;
    m.scale.x = m.scale.y = m.scale.z = config.mesh_scale;
    return m;
  }
  m.type = visualization_msgs::Marker::POINTS;
  m.scale.x = m.scale.y = std::max(0.002f, model.sampling_radius);
  const size_t stride =
      std::max<size_t>(1, (model.size() + kMaxMarkerPoints - 1) / kMaxMarkerPoints);
  for (size_t i = 0; i < model.size(); i += stride) {
    geometry_msgs::Point p;
    p.x = model.points[i].x();
    p.y = model.points[i].y();
    p.z = model.points[i].z();
    m.points.push_back(p);
  }
  return m;
}

Eigen::Vector3d labelPositionAbove(const stocs::ObjectModel& model, const Eigen::Isometry3d& pose,
                                   double text_height) {
  // In normalized image coordinates (x / z, y / z), so that the label is above the object as the
  // camera sees it, whatever the depth of its top point; the camera's up is -y.
  double left = std::numeric_limits<double>::infinity(), right = -left, top = left;
  double near = left, far = -left;
  for (const Eigen::Vector3f& p : model.points) {
    const Eigen::Vector3d q = pose * p.cast<double>();
    if (q.z() <= 0) continue;
    left = std::min(left, q.x() / q.z());
    right = std::max(right, q.x() / q.z());
    top = std::min(top, q.y() / q.z());
    near = std::min(near, q.z());
    far = std::max(far, q.z());
  }
  if (!(near <= far)) return pose.translation();  // no model point in front of the camera
  // rviz centres the text on its position.
  const double depth = (near + far) / 2;
  return {depth * (left + right) / 2, depth * top - 0.75 * text_height, depth};
}

void deleteMarkersNoLongerShown(visualization_msgs::MarkerArray& markers,
                                std::set<MarkerKey>& shown) {
  std::set<MarkerKey> now;
  for (const visualization_msgs::Marker& m : markers.markers) {
    if (m.action == visualization_msgs::Marker::ADD) now.insert({m.ns, m.id});
  }
  for (const MarkerKey& key : shown) {
    if (now.count(key)) continue;
    visualization_msgs::Marker m;
    m.ns = key.first;
    m.id = key.second;
    m.action = visualization_msgs::Marker::DELETE;
    markers.markers.push_back(m);
  }
  shown = std::move(now);
}

}  // namespace stocs_ros
