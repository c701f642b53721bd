#include "stocs_ros/scene_publisher/ground_truth_markers.h"

#include <ros/console.h>

#include "stocs/io/mesh_io.h"
#include "stocs/util/error.h"

namespace stocs_ros {
namespace {

/// Translucent green: the estimates, drawn opaque in each object's own colour, show through it.
std_msgs::ColorRGBA truthColour() {
  std_msgs::ColorRGBA c;
  c.r = 0.1f;
  c.g = 0.9f;
  c.b = 0.2f;
  c.a = 0.5f;
  return c;
}

}  // namespace

visualization_msgs::MarkerArray GroundTruthMarkers::build(const std::vector<TruthPose>& truth,
                                                          const std_msgs::Header& header) {
  visualization_msgs::MarkerArray out;
  for (const TruthPose& t : truth) {
    const int object = config_.objectIndex(t.object);
    if (object < 0) continue;
    const ObjectConfig& config = config_.objects[object];
    const stocs::ObjectModel& samples = model(object);
    if (config.mesh_url.empty() && samples.points.empty()) continue;
    visualization_msgs::Marker m = bodyMarker(config, samples, t.pose, truthColour());
    m.ns = "gt_" + t.object;
    m.id = static_cast<int>(t.instance);
    out.markers.push_back(std::move(m));
  }
  deleteMarkersNoLongerShown(out, shown_);
  for (visualization_msgs::Marker& m : out.markers) m.header = header;
  return out;
}

const stocs::ObjectModel& GroundTruthMarkers::model(size_t object) {
  const auto known = models_.find(object);
  if (known != models_.end()) return known->second;
  stocs::ObjectModel& m = models_[object];
  const ObjectConfig& config = config_.objects[object];
  if (!config.mesh_url.empty()) return m;
  try {
    m = stocs::prepareModel(stocs::loadMesh(config.model.string(), config.unit_scale),
                            config_.estimation.model.sampling);
  } catch (const stocs::InputError& e) {
    ROS_ERROR("scene_publisher: no ground-truth marker of '%s': %s", config.name.c_str(), e.what());
  }
  return m;
}

}  // namespace stocs_ros
