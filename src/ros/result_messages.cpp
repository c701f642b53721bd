#include "stocs_ros/result_messages.h"

#include <fmt/format.h>
#include <tf2_eigen/tf2_eigen.h>

#include <cmath>

namespace stocs_ros {
namespace {

/// Label text height, metres.
constexpr double kLabelHeight = 0.025;

geometry_msgs::Pose poseMsg(const Eigen::Isometry3f& pose) {
  return tf2::toMsg(Eigen::Isometry3d(pose.cast<double>()));
}

std_msgs::ColorRGBA colour(size_t object) {
  // Distinct hues, one per object: golden-ratio steps along the hue circle without its greens
  // (80 to 180 degrees), which mark the ground truth; object 0 is red.
  constexpr float kFirst = 180, kSpan = 260;  // degrees: cyan, blue, magenta, red, orange, yellow
  const float step =
      std::fmod((360 - kFirst) / kSpan + 0.6180339f * static_cast<float>(object), 1.0f);
  const float hue = std::fmod(kFirst + kSpan * step, 360.0f) / 60.0f;
  const float x = 1.0f - std::abs(std::fmod(hue, 2.0f) - 1.0f);
  const float rgb[6][3] = {{1, x, 0}, {x, 1, 0}, {0, 1, x}, {0, x, 1}, {x, 0, 1}, {1, 0, x}};
  const float* c = rgb[static_cast<int>(hue) % 6];
  std_msgs::ColorRGBA out;
  out.r = c[0];
  out.g = c[1];
  out.b = c[2];
  out.a = 1.0f;
  return out;
}

visualization_msgs::Marker objectBodyMarker(const FoundPose& f, const EstimationSetup& setup) {
  const size_t object = f.outcome->object;
  visualization_msgs::Marker m =
      bodyMarker(setup.config.objects[object], setup.models[object].model,
                 Eigen::Isometry3d(f.pose.cast<double>()), colour(object));
  m.ns = setup.config.objects[object].name;
  m.id = static_cast<int>(2 * f.instance);
  return m;
}

visualization_msgs::Marker labelMarker(const FoundPose& f, const EstimationSetup& setup) {
  const size_t object = f.outcome->object;
  visualization_msgs::Marker m;
  m.ns = setup.config.objects[object].name;
  m.id = static_cast<int>(2 * f.instance + 1);
  m.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
  m.action = visualization_msgs::Marker::ADD;
  m.text = fmt::format("{} {:.3f}", instanceName(m.ns, f.instance), f.score);
  m.pose.orientation.w = 1;
  m.pose.position = tf2::toMsg(labelPositionAbove(
      setup.models[object].model, Eigen::Isometry3d(f.pose.cast<double>()), kLabelHeight));
  m.scale.z = kLabelHeight;
  m.color.r = m.color.g = m.color.b = m.color.a = 1;
  return m;
}

}  // namespace

std::vector<FoundPose> foundPoses(const FrameResult& result) {
  std::vector<FoundPose> out;
  for (const ObjectOutcome& o : result.objects) {
    const stocs::PoseEstimate& e = o.estimate;
    if (!e.found) continue;
    if (e.instances.empty()) {
      out.push_back({&o, 0, e.pose, e.score});
      continue;
    }
    for (size_t k = 0; k < e.instances.size(); ++k) {
      out.push_back({&o, k, e.instances[k].pose, e.instances[k].score});
    }
  }
  return out;
}

std::string instanceName(const std::string& object, size_t instance) {
  return instance == 0 ? object : fmt::format("{}_{}", object, instance);
}

ObjectPoseArray toObjectPoseArray(const FrameResult& result, const EstimationSetup& setup) {
  ObjectPoseArray out;
  out.header = result.header;
  for (const FoundPose& f : foundPoses(result)) {
    const ObjectConfig& config = setup.config.objects[f.outcome->object];
    ObjectPose p;
    p.name = config.name;
    p.id = config.id;
    p.instance = static_cast<uint32_t>(f.instance);
    p.score = f.score;
    p.pose = poseMsg(f.pose);
    p.estimation_time = f.outcome->estimate.seconds;
    p.hypotheses_verified = f.outcome->estimate.hypotheses;
    out.objects.push_back(p);
  }
  return out;
}

geometry_msgs::PoseArray toPoseArray(const FrameResult& result) {
  geometry_msgs::PoseArray out;
  out.header = result.header;
  for (const FoundPose& f : foundPoses(result)) out.poses.push_back(poseMsg(f.pose));
  return out;
}

visualization_msgs::MarkerArray toMarkers(const FrameResult& result, const EstimationSetup& setup,
                                          std::set<MarkerKey>& shown) {
  visualization_msgs::MarkerArray out;
  for (const FoundPose& f : foundPoses(result)) {
    out.markers.push_back(objectBodyMarker(f, setup));
    out.markers.push_back(labelMarker(f, setup));
  }
  separateOverlappingLabels(out);
  deleteMarkersNoLongerShown(out, shown);
  for (visualization_msgs::Marker& m : out.markers) m.header = result.header;
  return out;
}

}  // namespace stocs_ros
