#include "stocs_ros/stocs_node/result_messages.h"

#include <fmt/format.h>
#include <tf2_eigen/tf2_eigen.h>

#include <cmath>

#include "stocs_ros/stocs_node/pose_uncertainty.h"

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
      bodyMarker(setup.config.objects[object], setup.models[object]->model,
                 Eigen::Isometry3d(f.estimate.pose.cast<double>()), colour(object));
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
  // The confidence, not the score: the score ranks one frame's hypotheses and means nothing to a
  // reader (issue 42: "cat 0.088" for a pose of confidence 0.54).
  m.text = fmt::format("{} {:.2f}", instanceName(m.ns, f.instance), f.estimate.confidence);
  m.pose.orientation.w = 1;
  m.pose.position = tf2::toMsg(labelPositionAbove(setup.models[object]->model,
                                                  Eigen::Isometry3d(f.estimate.pose.cast<double>()),
                                                  kLabelHeight));
  m.scale.z = kLabelHeight;
  m.color.r = m.color.g = m.color.b = m.color.a = 1;
  return m;
}

stocs::PoseCovariance covarianceOf(const FoundPose& f, const EstimationSetup& setup) {
  return publishableCovariance(f.estimate.covariance, f.estimate.pose,
                               setup.models[f.outcome->object]->model);
}

visualization_msgs::Marker objectUncertaintyMarker(const FoundPose& f,
                                                   const EstimationSetup& setup) {
  const size_t object = f.outcome->object;
  // At least the object's size across: a 90% ellipsoid of a few millimetres hides inside the
  // opaque body.
  visualization_msgs::Marker m =
      uncertaintyMarker(f.estimate.pose, covarianceOf(f, setup), colour(object),
                        kUncertaintyMinimumShare * setup.models[object]->model.diameter);
  m.ns = kUncertaintyNamespace;
  m.id = kUncertaintyIdsPerObject * static_cast<int>(object) + static_cast<int>(f.instance);
  return m;
}

/// A message about `f` with its object's name and id, its instance and its confidence.
template <class Message>
Message identifiedMessage(const FoundPose& f, const EstimationSetup& setup) {
  const ObjectConfig& config = setup.config.objects[f.outcome->object];
  Message m;
  m.name = config.name;
  m.id = config.id;
  m.instance = static_cast<uint32_t>(f.instance);
  m.confidence = f.estimate.confidence;
  return m;
}

/// How `f`'s pose came about (ObjectPose::state): detected unless its object was tracked.
uint8_t stateOf(const FoundPose& f) {
  const std::vector<stocs::TrackState>& states = f.outcome->states;
  if (f.instance >= states.size()) return ObjectPose::DETECTED;
  return states[f.instance] == stocs::TrackState::kTracked ? ObjectPose::TRACKED
                                                           : ObjectPose::REDETECTED;
}

/// Whether `f` is a tracked instance in `state` (RejectedObject::lost, hidden).
bool poseIn(const FoundPose& f, stocs::TrackState state) {
  const std::vector<stocs::TrackState>& states = f.outcome->states;
  return f.instance < states.size() && states[f.instance] == state;
}

/// Every pose of the result whose acceptance is `accepted`.
std::vector<FoundPose> posesAccepted(const FrameResult& result, bool accepted) {
  std::vector<FoundPose> out;
  for (const ObjectOutcome& o : result.objects) {
    const stocs::PoseEstimate& e = o.estimate;
    if (!e.found()) continue;
    for (size_t k = 0; k < e.instances.size(); ++k) {
      if (e.instances[k].accepted == accepted) out.push_back({&o, k, e.instances[k]});
    }
  }
  return out;
}

}  // namespace

std::vector<FoundPose> foundPoses(const FrameResult& result) {
  return posesAccepted(result, true);
}

std::vector<FoundPose> rejectedPoses(const FrameResult& result) {
  return posesAccepted(result, false);
}

std::string rejectionReason(const FoundPose& rejected) {
  return rejected.estimate.rejection.empty() ? "rejected" : rejected.estimate.rejection;
}

ObjectPoseArray toObjectPoseArray(const FrameResult& result, const EstimationSetup& setup) {
  ObjectPoseArray out;
  out.header = result.header;
  for (const FoundPose& f : foundPoses(result)) {
    ObjectPose p = identifiedMessage<ObjectPose>(f, setup);
    p.score = f.estimate.score;
    p.pose.pose = poseMsg(f.estimate.pose);
    p.pose.covariance = covarianceMsg(covarianceOf(f, setup));
    p.estimation_time = f.outcome->estimate.seconds;
    p.hypotheses_verified = f.outcome->estimate.hypotheses;
    p.state = stateOf(f);
    if (!f.estimate.ambiguous.empty()) p.ambiguity = stocs::ambiguityText(f.estimate.ambiguous);
    out.objects.push_back(p);
  }
  for (const FoundPose& f : rejectedPoses(result)) {
    RejectedObject r = identifiedMessage<RejectedObject>(f, setup);
    r.reason = rejectionReason(f);
    r.lost = poseIn(f, stocs::TrackState::kLost);
    r.hidden = poseIn(f, stocs::TrackState::kHidden);
    out.rejected.push_back(r);
  }
  return out;
}

geometry_msgs::PoseWithCovarianceStamped toPoseWithCovariance(const FoundPose& found,
                                                              const FrameResult& result,
                                                              const EstimationSetup& setup) {
  geometry_msgs::PoseWithCovarianceStamped out;
  out.header = result.header;
  out.pose.pose = poseMsg(found.estimate.pose);
  out.pose.covariance = covarianceMsg(covarianceOf(found, setup));
  return out;
}

geometry_msgs::PoseArray toPoseArray(const FrameResult& result) {
  geometry_msgs::PoseArray out;
  out.header = result.header;
  for (const FoundPose& f : foundPoses(result)) out.poses.push_back(poseMsg(f.estimate.pose));
  return out;
}

visualization_msgs::MarkerArray toMarkers(const FrameResult& result, const EstimationSetup& setup,
                                          std::set<MarkerKey>& shown) {
  visualization_msgs::MarkerArray out;
  for (const FoundPose& f : foundPoses(result)) {
    out.markers.push_back(objectBodyMarker(f, setup));
    out.markers.push_back(labelMarker(f, setup));
  }
  for (const FoundPose& f : foundPoses(result)) {
    out.markers.push_back(objectUncertaintyMarker(f, setup));
  }
  separateOverlappingLabels(out);
  deleteMarkersNoLongerShown(out, shown);
  for (visualization_msgs::Marker& m : out.markers) m.header = result.header;
  return out;
}

}  // namespace stocs_ros
