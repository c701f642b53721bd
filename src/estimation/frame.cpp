#include "stocs/estimation/frame.h"

#include <fmt/format.h>

#include <algorithm>

#include "frame_explainer.h"
#include "frame_internal.h"
#include "stocs/geometry/mesh.h"
#include "stocs/util/cpu_time.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

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

}  // namespace

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

void estimateObject(const ObjectInput& input, const ObjectEstimator& estimate,
                    ObjectResult& result) {
  const double cpu_start = processCpuSeconds();
  result.estimate = estimate(input);
  result.cpu_seconds = processCpuSeconds() - cpu_start;
}

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

PipelineParams paramsForMaps(const Frame& frame, const PipelineParams& params) {
  if (frame.maps_name_objects) return params;
  PipelineParams p = params;
  p.confidence = params.confidence.forDepthAloneMaps();
  return p;
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
                                        const PipelineParams& requested,
                                        const ObjectEstimator& estimate) {
  const PipelineParams params = paramsForMaps(frame, requested);
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
  FrameExplainer explanation(frame, camera, objects, params);
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
  FrameExplainer(frame, camera, objects, paramsForMaps(frame, params)).explain(estimates);
}

}  // namespace stocs
