#include "stocs/estimation/frame.h"

#include <fmt/format.h>

#include <algorithm>

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
  for (const FrameObject& object : objects) {
    frame.probabilities[object.name] =
        objectProbability(segmentation, modelSize(object.model->model), segmenter.params());
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
      const ObjectInput input = objectInput(frame, camera, object, params);
      ObjectResult result;
      result.name = object.name;
      const double cpu_start = processCpuSeconds();
      result.estimate = estimate(input);
      result.cpu_seconds = processCpuSeconds() - cpu_start;
      results.push_back(std::move(result));
    });
  }
  std::vector<PoseEstimate*> estimates;
  for (ObjectResult& result : results) estimates.push_back(&result.estimate);
  explainFrame(frame, camera, objects, estimates, params);
  return results;
}

void explainFrame(const Frame& frame, const CameraIntrinsics& camera,
                  const std::vector<FrameObject>& objects,
                  const std::vector<PoseEstimate*>& estimates, const PipelineParams& params) {
  if (!params.explanation.enabled) return;
  std::vector<FramePose> poses;
  for (size_t i = 0; i < estimates.size(); ++i) {
    const cv::Mat* map = &probabilityOf(frame, objects[i].name);
    std::vector<InstancePose>& instances = estimates[i]->instances;
    for (size_t k = 0; k < instances.size(); ++k) {
      poses.push_back(
          {objects[i].name, static_cast<int>(k), &objects[i].model->model, map, &instances[k]});
    }
  }
  explainPoses(poses, FreeSpaceCheck(frame.cloud, camera, params.stocs.free_space),
               params.explanation);
}

}  // namespace stocs
