#include "stocs_ros/result_messages.h"

#include <fmt/format.h>
#include <tf2_eigen/tf2_eigen.h>

#include <algorithm>
#include <cmath>

namespace stocs_ros {
namespace {

/// Enough points to show the shape; rviz slows down with whole models of many objects.
constexpr size_t kMaxMarkerPoints = 2000;

geometry_msgs::Pose poseMsg(const Eigen::Isometry3f& pose) {
  return tf2::toMsg(Eigen::Isometry3d(pose.cast<double>()));
}

std_msgs::ColorRGBA colour(size_t object) {
  // Distinct hues, one per object (golden-ratio steps around the colour wheel).
  const float hue = std::fmod(0.6180339f * static_cast<float>(object), 1.0f) * 6.0f;
  const float x = 1.0f - std::abs(std::fmod(hue, 2.0f) - 1.0f);
  const float rgb[6][3] = {{1, x, 0}, {x, 1, 0}, {0, 1, x}, {0, x, 1}, {x, 0, 1}, {1, 0, x}};
  const float* c = rgb[static_cast<int>(hue) % 6];
  std_msgs::ColorRGBA out;
  out.r = c[0];
  out.g = c[1];
  out.b = c[2];
  out.a = 0.8f;
  return out;
}

visualization_msgs::Marker bodyMarker(const ObjectOutcome& o, const EstimationSetup& setup) {
  const ObjectConfig& config = setup.config.objects[o.object];
  visualization_msgs::Marker m;
  m.ns = config.name;
  m.id = 0;
  m.action = visualization_msgs::Marker::ADD;
  m.pose = poseMsg(o.estimate.estimate.pose);
  m.color = colour(o.object);
  if (!config.mesh_url.empty()) {
    m.type = visualization_msgs::Marker::MESH_RESOURCE;
    m.mesh_resource = config.mesh_url;
    m.scale.x = m.scale.y = m.scale.z = config.mesh_scale;
    return m;
  }
  const std::vector<Eigen::Vector3f>& samples = setup.models[o.object].model.points;
  m.type = visualization_msgs::Marker::POINTS;
  m.scale.x = m.scale.y = std::max(0.002f, setup.models[o.object].model.sampling_radius);
  const size_t stride =
      std::max<size_t>(1, (samples.size() + kMaxMarkerPoints - 1) / kMaxMarkerPoints);
  for (size_t i = 0; i < samples.size(); i += stride) {
    geometry_msgs::Point p;
    p.x = samples[i].x();
    p.y = samples[i].y();
    p.z = samples[i].z();
    m.points.push_back(p);
  }
  return m;
}

visualization_msgs::Marker labelMarker(const ObjectOutcome& o, const EstimationSetup& setup) {
  visualization_msgs::Marker m;
  m.ns = setup.config.objects[o.object].name;
  m.id = 1;
  m.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
  m.action = visualization_msgs::Marker::ADD;
  m.text = fmt::format("{} {:.3f}", m.ns, o.estimate.estimate.lcp.score);
  m.pose.orientation.w = 1;
  // Above the object: optical frames have y pointing down.
  const Eigen::Vector3f at = o.estimate.estimate.pose.translation() -
                             Eigen::Vector3f(0, 0.6f * setup.models[o.object].model.diameter, 0);
  m.pose.position.x = at.x();
  m.pose.position.y = at.y();
  m.pose.position.z = at.z();
  m.scale.z = 0.02;
  m.color.r = m.color.g = m.color.b = m.color.a = 1;
  return m;
}

}  // namespace

ObjectPoseArray toObjectPoseArray(const FrameResult& result, const EstimationSetup& setup) {
  ObjectPoseArray out;
  out.header = result.header;
  for (const ObjectOutcome& o : result.objects) {
    if (!o.estimate.estimate.found) continue;
    ObjectPose p;
    p.name = setup.config.objects[o.object].name;
    p.id = setup.config.objects[o.object].id;
    p.score = o.estimate.estimate.lcp.score;
    p.pose = poseMsg(o.estimate.estimate.pose);
    p.estimation_time = o.estimate.seconds;
    p.hypotheses_verified = o.estimate.estimate.hypotheses;
    out.objects.push_back(p);
  }
  return out;
}

geometry_msgs::PoseArray toPoseArray(const FrameResult& result) {
  geometry_msgs::PoseArray out;
  out.header = result.header;
  for (const ObjectOutcome& o : result.objects) {
    if (o.estimate.estimate.found) out.poses.push_back(poseMsg(o.estimate.estimate.pose));
  }
  return out;
}

visualization_msgs::MarkerArray toMarkers(const FrameResult& result, const EstimationSetup& setup,
                                          std::set<std::string>& shown) {
  visualization_msgs::MarkerArray out;
  std::set<std::string> now;
  for (const ObjectOutcome& o : result.objects) {
    if (!o.estimate.estimate.found) continue;
    out.markers.push_back(bodyMarker(o, setup));
    out.markers.push_back(labelMarker(o, setup));
    now.insert(setup.config.objects[o.object].name);
  }
  for (const std::string& name : shown) {
    if (now.count(name)) continue;
    for (int id : {0, 1}) {
      visualization_msgs::Marker m;
      m.ns = name;
      m.id = id;
      m.action = visualization_msgs::Marker::DELETE;
      out.markers.push_back(m);
    }
  }
  for (visualization_msgs::Marker& m : out.markers) m.header = result.header;
  shown = std::move(now);
  return out;
}

}  // namespace stocs_ros
