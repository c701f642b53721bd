#include "stocs_ros/common/object_markers.h"

#include <tf2_eigen/tf2_eigen.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

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

namespace {

/// A label's box in normalized image coordinates (x / z, y / z; y down).
struct LabelBox {
  visualization_msgs::Marker* marker;
  double u, v, half_width, half_height;

  bool overlaps(const LabelBox& o) const {
    return std::abs(u - o.u) < half_width + o.half_width &&
           std::abs(v - o.v) < half_height + o.half_height;
  }
};

}  // namespace

void separateOverlappingLabels(visualization_msgs::MarkerArray& markers) {
  std::vector<LabelBox> boxes;
  for (visualization_msgs::Marker& m : markers.markers) {
    const double z = m.pose.position.z;
    if (m.type != visualization_msgs::Marker::TEXT_VIEW_FACING || !(z > 0)) continue;
    const double height = m.scale.z / z;
    boxes.push_back({&m, m.pose.position.x / z, m.pose.position.y / z,
                     kLabelCharWidth * height * static_cast<double>(m.text.size()) / 2,
                     height / 2});
  }
  std::sort(boxes.begin(), boxes.end(),
            [](const LabelBox& a, const LabelBox& b) { return a.v > b.v; });
  for (auto box = boxes.begin(); box != boxes.end(); ++box) {
    // Each move puts the label above a placed one, higher than before, so this ends. The gap of a
    // fifth of the label's height keeps the two apart whatever the rounding.
    for (auto placed = boxes.begin(); placed != box;) {
      if (!box->overlaps(*placed)) {
        ++placed;
        continue;
      }
      box->v = placed->v - placed->half_height - 1.4 * box->half_height;
      placed = boxes.begin();
    }
    box->marker->pose.position.y = box->v * box->marker->pose.position.z;
  }
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
