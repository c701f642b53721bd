#include "stocs/estimation/frame.h"

#include <fmt/format.h>

#include <algorithm>

#include "stocs/estimation/stages/frame_explanation.h"
#include "stocs/geometry/mesh.h"
#include "stocs/util/cpu_time.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

/// The probability map of `name` in `frame`, checked against the cloud's size.
const cv::Mat& probabilityOf(const Frame& frame, const std::string& name) {
  const auto it = frame.probabilities.find(name);
  if (it == frame.probabilities.end() || it->second.empty()) {
    throw InputError("the frame has no probability image");
  }
  if (it->second.cols != frame.cloud.width || it->second.rows != frame.cloud.height) {
    throw InputError(fmt::format("probability image is {}x{} but the cloud is {}x{}",
                                 it->second.cols, it->second.rows, frame.cloud.width,
                                 frame.cloud.height));
  }
  return it->second;
}

/// The frame's colour image, checked against the cloud's size and type; null when it has none.
const cv::Mat* colourOf(const Frame& frame) {
  const cv::Mat& colour = frame.colour;
  if (colour.empty()) return nullptr;
  if (colour.type() != CV_8UC3) {
    throw InputError(
        fmt::format("colour image must be 8-bit BGR (CV_8UC3), not type {}", colour.type()));
  }
  if (colour.cols != frame.cloud.width || colour.rows != frame.cloud.height) {
    throw InputError(fmt::format("colour image {}x{} does not fit the {}x{} cloud", colour.cols,
                                 colour.rows, frame.cloud.width, frame.cloud.height));
  }
  return &colour;
}

/// Runs `estimate` on `input` into `result`: the estimate and the CPU time it took.
void estimateObject(const ObjectInput& input, const ObjectEstimator& estimate,
                    ObjectResult& result) {
  const double cpu_start = processCpuSeconds();
  result.estimate = estimate(input);
  result.cpu_seconds = processCpuSeconds() - cpu_start;
}

bool anyAccepted(const PoseEstimate& estimate) {
  return std::any_of(estimate.instances.begin(), estimate.instances.end(),
                     [](const InstancePose& p) { return p.accepted; });
}

/// The frame-level explanation of one frame's objects (explainPoses), and the second search of an
/// object whose every pose other objects' poses explain.
class FrameExplanation {
 public:
  FrameExplanation(const Frame& frame, const CameraIntrinsics& camera,
                   const std::vector<FrameObject>& objects, const PipelineParams& params)
      : frame_(frame),
        camera_(camera),
        objects_(objects),
        params_(params),
        visibility_(frame.cloud, camera, params.stocs.free_space) {
    for (const FrameObject& object : objects) maps_.push_back(&probabilityOf(frame, object.name));
  }

  /// explainPoses over every instance of `estimates[i]`, the estimate of object i.
  std::vector<ExplainedPose> explain(const std::vector<PoseEstimate*>& estimates) {
    collect(estimates);
    return explainPoses(poses_, visibility_, params_.explanation, frame_.maps_name_objects);
  }
  std::vector<ExplainedPose> explain(std::vector<ObjectResult>& results) {
    return explain(estimatesOf(results));
  }

  /// The objects, once each, that `explained` (the last explain()'s) left without an accepted
  /// pose while another object's pose explains one of theirs.
  std::vector<size_t> displaced(const std::vector<ExplainedPose>& explained) const {
    std::vector<size_t> out;
    for (const ExplainedPose& e : explained) {
      const size_t object = owners_[e.pose];
      if (owners_[e.by] == object || std::count(out.begin(), out.end(), object) > 0) continue;
      if (!anyAccepted(*estimates_[object])) out.push_back(object);
    }
    return out;
  }

  /// Object i searched for again (`estimate`) on its map without the surface that the accepted
  /// poses of the other objects confirm. Its new estimate is kept when, explained again with the
  /// others, it has an accepted pose; otherwise every pose is as before. Either way results[i]
  /// counts the time of both searches.
  void searchAgain(size_t i, const ObjectEstimator& estimate, std::vector<ObjectResult>& results) {
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

 private:
  static std::vector<PoseEstimate*> estimatesOf(std::vector<ObjectResult>& results) {
    std::vector<PoseEstimate*> estimates;
    for (ObjectResult& result : results) estimates.push_back(&result.estimate);
    return estimates;
  }

  /// Every instance of `estimates` as a pose of the explanation.
  void collect(const std::vector<PoseEstimate*>& estimates) {
    estimates_ = estimates;
    poses_.clear();
    owners_.clear();
    for (size_t i = 0; i < estimates.size(); ++i) {
      std::vector<InstancePose>& instances = estimates[i]->instances;
      for (size_t k = 0; k < instances.size(); ++k) {
        poses_.push_back({objects_[i].name, static_cast<int>(k), &objects_[i].model->model,
                          maps_[i], &instances[k]});
        owners_.push_back(i);
      }
    }
  }

  const Frame& frame_;
  const CameraIntrinsics& camera_;
  const std::vector<FrameObject>& objects_;
  const PipelineParams& params_;
  const FreeSpaceCheck visibility_;
  std::vector<const cv::Mat*> maps_;  ///< per object: its map, or the map it was searched on again
  std::map<size_t, cv::Mat> masked_;  ///< the maps objects were searched on again, by object
  std::vector<PoseEstimate*> estimates_;  ///< of the last collect()
  std::vector<FramePose> poses_;          ///< of the last collect()
  std::vector<size_t> owners_;            ///< per pose of poses_: its object's index
};

}  // namespace

Frame Frame::fromDepth(const cv::Mat& depth, const CameraIntrinsics& camera,
                       double metres_per_unit) {
  Frame frame;
  frame.cloud = cloudFromDepth(depth, camera, metres_per_unit);
  frame.camera = camera;
  return frame;
}

PoseEstimate detectObject(const ObjectInput& in) {
  return detectObject(*in.cloud, static_cast<float>(in.camera->fx), *in.probability, *in.model,
                      *in.params, in.boundary, in.camera, in.colour);
}

ObjectSize modelSize(const ObjectModel& model) {
  constexpr size_t kWidthSamples = 1000;  // enough for a width within a millimetre or two
  const size_t n = std::min(model.points.size(), kWidthSamples);
  const std::vector<Eigen::Vector3f> prefix(model.points.begin(), model.points.begin() + n);
  return {model.diameter, pointSetMinWidth(prefix)};
}

GeometricSegmentation setGeometricProbabilities(Frame& frame,
                                                const std::vector<FrameObject>& objects,
                                                GeometricSegmenter& segmenter) {
  GeometricSegmentation segmentation = segmenter.segment(frame.cloud, frameCamera(frame));
  if (const cv::Mat* colour = colourOf(frame)) addRegionColours(segmentation, *colour);
  frame.maps_name_objects = false;
  for (const FrameObject& object : objects) {
    const ObjectModel& model = object.model->model;
    const ChromaticityHistogram colours = ChromaticityHistogram::of(model.colours);
    frame.probabilities[object.name] =
        objectProbability(segmentation, modelSize(model), segmenter.params(), &colours);
  }
  return segmentation;
}

CameraIntrinsics frameCamera(const Frame& frame) {
  return frame.camera ? *frame.camera : intrinsicsFromCloud(frame.cloud);
}

ObjectInput objectInput(const Frame& frame, const CameraIntrinsics& camera,
                        const FrameObject& object, const PipelineParams& params) {
  ObjectInput input;
  input.cloud = &frame.cloud;
  input.camera = &camera;
  input.probability = &probabilityOf(frame, object.name);
  input.boundary = frame.boundary.empty() ? nullptr : &frame.boundary;
  input.colour = colourOf(frame);
  input.model = object.model;
  input.params = &params;
  return input;
}

void forObject(const std::string& name, const std::function<void()>& step) {
  try {
    step();
  } catch (const InputError& e) {
    throw InputError(fmt::format("object '{}': {}", name, e.what()));
  }
}

std::vector<ObjectResult> estimateFrame(const Frame& frame, const std::vector<FrameObject>& objects,
                                        const PipelineParams& params) {
  return estimateFrame(frame, objects, params,
                       [](const ObjectInput& in) { return detectObject(in); });
}

std::vector<ObjectResult> estimateFrame(const Frame& frame, const std::vector<FrameObject>& objects,
                                        const PipelineParams& params,
                                        const ObjectEstimator& estimate) {
  const CameraIntrinsics camera = frameCamera(frame);
  std::vector<ObjectResult> results;
  for (const FrameObject& object : objects) {
    forObject(object.name, [&] {
      ObjectResult result;
      result.name = object.name;
      estimateObject(objectInput(frame, camera, object, params), estimate, result);
      results.push_back(std::move(result));
    });
  }
  if (!params.explanation.enabled) return results;
  FrameExplanation explanation(frame, camera, objects, params);
  const std::vector<ExplainedPose> explained = explanation.explain(results);
  if (!params.explanation.search_again) return results;
  for (size_t i : explanation.displaced(explained)) {
    forObject(objects[i].name, [&] { explanation.searchAgain(i, estimate, results); });
  }
  return results;
}

void explainFrame(const Frame& frame, const CameraIntrinsics& camera,
                  const std::vector<FrameObject>& objects,
                  const std::vector<PoseEstimate*>& estimates, const PipelineParams& params) {
  if (!params.explanation.enabled) return;
  FrameExplanation(frame, camera, objects, params).explain(estimates);
}

}  // namespace stocs
