#include "frame_explainer.h"

#include <algorithm>

#include "frame_internal.h"
#include "stocs/estimation/stages/pose_confidence.h"

namespace stocs {
namespace {

bool anyAccepted(const PoseEstimate& estimate) {
  return std::any_of(estimate.instances.begin(), estimate.instances.end(),
                     [](const InstancePose& p) { return p.accepted; });
}

std::vector<PoseEstimate*> estimatesOf(std::vector<ObjectResult>& results) {
  std::vector<PoseEstimate*> estimates;
  for (ObjectResult& result : results) estimates.push_back(&result.estimate);
  return estimates;
}

}  // namespace

FrameExplainer::FrameExplainer(const Frame& frame, const CameraIntrinsics& camera,
                               const std::vector<FrameObject>& objects,
                               const PipelineParams& params)
    : frame_(frame),
      camera_(camera),
      objects_(objects),
      params_(params),
      visibility_(frame.cloud, camera, params.stocs.free_space) {
  for (const FrameObject& object : objects) maps_.push_back(&probabilityOf(frame, object.name));
}

std::vector<ExplainedPose> FrameExplainer::explain(const std::vector<PoseEstimate*>& estimates) {
  collect(estimates);
  std::vector<float> before;
  for (const FramePose& p : poses_) before.push_back(p.pose->evidence.explained);
  std::vector<ObjectMap> maps;
  for (size_t i = 0; i < objects_.size(); ++i) maps.push_back({objects_[i].name, maps_[i]});
  std::vector<ExplainedPose> explained =
      explainPoses(poses_, visibility_, params_.explanation, frame_.maps_name_objects, maps);
  // The confidence reads the share others explain: poses whose share changed are judged again;
  // the rejected ones keep their reason (`explained by`, `claimed by the map of`).
  for (size_t i = 0; i < poses_.size(); ++i) {
    InstancePose& pose = *poses_[i].pose;
    if (pose.evidence.explained == before[i]) continue;
    if (pose.accepted) {
      judgePose(pose, params_.confidence);
    } else {
      pose.confidence = params_.confidence.confidence(pose.evidence);
    }
  }
  return explained;
}

std::vector<ExplainedPose> FrameExplainer::explain(std::vector<ObjectResult>& results) {
  return explain(estimatesOf(results));
}

std::vector<size_t> FrameExplainer::displaced(const std::vector<ExplainedPose>& explained) const {
  std::vector<size_t> out;
  for (const ExplainedPose& e : explained) {
    const size_t object = owners_[e.pose];
    if (owners_[e.by] == object || std::count(out.begin(), out.end(), object) > 0) continue;
    if (!anyAccepted(*estimates_[object])) out.push_back(object);
  }
  return out;
}

void FrameExplainer::searchAgain(size_t i, const ObjectEstimator& estimate,
                                 std::vector<ObjectResult>& results) {
  std::vector<bool> others(poses_.size());
  for (size_t p = 0; p < poses_.size(); ++p) others[p] = owners_[p] != i;
  cv::Mat masked = maps_[i]->clone();
  masked.setTo(0, confirmedArea(poses_, others, visibility_));
  ObjectInput input = objectInput(frame_, camera_, objects_[i], params_);
  input.probability = &masked;
  ObjectResult again{results[i].name, {}, 0};
  estimateObject(input, estimate, again);
  const double cpu = results[i].cpu_seconds + again.cpu_seconds;
  const double seconds = results[i].estimate.seconds + again.estimate.seconds;
  if (anyAccepted(again.estimate)) {
    std::vector<ObjectResult> before = results;
    const cv::Mat* map = maps_[i];
    results[i] = std::move(again);
    maps_[i] = &(masked_[i] = masked);
    explain(results);
    if (!anyAccepted(results[i].estimate)) {
      results = std::move(before);
      maps_[i] = map;
      collect(estimatesOf(results));
    }
  }
  results[i].cpu_seconds = cpu;
  results[i].estimate.seconds = seconds;
}

void FrameExplainer::collect(const std::vector<PoseEstimate*>& estimates) {
  estimates_ = estimates;
  poses_.clear();
  owners_.clear();
  for (size_t i = 0; i < estimates.size(); ++i) {
    std::vector<InstancePose>& instances = estimates[i]->instances;
    for (size_t k = 0; k < instances.size(); ++k) {
      poses_.push_back({objects_[i].name, static_cast<int>(k), &objects_[i].model->model, maps_[i],
                        &instances[k]});
      owners_.push_back(i);
    }
  }
}

}  // namespace stocs
