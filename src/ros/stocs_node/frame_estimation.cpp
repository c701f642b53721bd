#include "stocs_ros/stocs_node/frame_estimation.h"

#include <fmt/format.h>

#include <opencv2/core.hpp>
#include <stdexcept>

#include "stocs/util/error.h"
#include "stocs_ros/common/cloud_conversion.h"
#include "stocs_ros/common/image_conversion.h"
#include "stocs_ros/common/input_naming.h"
#include "stocs_ros/common/segmentation_conversion.h"

namespace stocs_ros {
using stocs::InputError;

namespace {

/// Probability images by object index (empty where the frame has none); `size`: the cloud's.
std::vector<cv::Mat> probabilities(const EstimationJob& job, const NodeConfig& config,
                                   cv::Size size) {
  const FrameMessages& frame = job.frame;
  if (config.input.segmentationForm()) {
    return probabilitiesFromSegmentation(frame.segmentation, job.objects, config, size);
  }
  std::vector<cv::Mat> out(config.objects.size());
  if (frame.multichannel) {
    const std::vector<cv::Mat> channels = naming("multi-channel probability image", [&] {
      return probabilitiesFromChannels(frame.multichannel, config.input.channels.size(),
                                       config.input.uint16_scale);
    });
    for (size_t c = 0; c < channels.size(); ++c) {
      const int object = config.objectIndex(config.input.channels[c]);
      if (object >= 0) out[object] = channels[c];
    }
    return out;
  }
  for (size_t i : job.objects) {
    if (i < frame.probabilities.size() && frame.probabilities[i]) {
      out[i] = naming(fmt::format("probability image of '{}'", config.objects[i].name), [&] {
        return probabilityFromImage(frame.probabilities[i], config.input.uint16_scale);
      });
    }
  }
  return out;
}

}  // namespace

const std_msgs::Header& FrameMessages::header() const {
  return cloud ? cloud->header : depth->header;
}

stocs::Frame convertFrame(const EstimationJob& job, const NodeConfig& config) {
  const FrameMessages& messages = job.frame;
  stocs::Frame frame;
  // The intrinsics once per frame: every object's free-space check projects with them.
  if (messages.cloud) {
    frame.cloud = naming("cloud", [&] { return cloudFromMsg(*messages.cloud); });
    frame.colour = naming("cloud", [&] { return colourFromCloudMsg(*messages.cloud); });
    frame.camera = naming("cloud", [&] { return intrinsicsFromCloud(frame.cloud); });
  } else {
    frame.cloud = naming(
        "depth image", [&] { return cloudFromDepthImage(messages.depth, *messages.camera_info); });
    frame.camera = intrinsicsFromCameraInfo(*messages.camera_info);
  }
  const std::vector<cv::Mat> probability =
      probabilities(job, config, cv::Size(frame.cloud.width, frame.cloud.height));
  for (size_t i = 0; i < probability.size(); ++i) {
    if (!probability[i].empty()) frame.probabilities[config.objects[i].name] = probability[i];
  }
  if (messages.boundary) {
    frame.boundary = naming("boundary image", [&] { return boundaryFromImage(messages.boundary); });
  }
  if (messages.colour) {
    frame.colour = naming("colour image", [&] {
      cv::Mat colour = colourFromImage(messages.colour);
      if (colour.cols != static_cast<int>(frame.cloud.width) ||
          colour.rows != static_cast<int>(frame.cloud.height)) {
        throw InputError(
            fmt::format("{}x{} image does not fit the {}x{} depth: it must be the "
                        "colour registered with the depth, pixel for pixel",
                        colour.cols, colour.rows, frame.cloud.width, frame.cloud.height));
      }
      return colour;
    });
  }
  return frame;
}

namespace {

/// The job's estimation parameters (its time budget instead of the configured one).
stocs::PipelineParams jobParams(const EstimationJob& job, const NodeConfig& config) {
  stocs::PipelineParams params = config.estimation;
  if (job.time_budget) params.stocs.time_budget = *job.time_budget;
  return params;
}

/// The job's objects for the core's frame loop.
std::vector<stocs::FrameObject> jobObjects(const EstimationJob& job, const EstimationSetup& setup) {
  std::vector<stocs::FrameObject> objects;
  for (size_t i : job.objects)
    objects.push_back({setup.config.objects[i].name, setup.models[i].get()});
  return objects;
}

}  // namespace

stocs::Frame estimationFrame(const EstimationJob& job, const EstimationSetup& setup,
                             stocs::GeometricSegmenter* geometric) {
  stocs::Frame frame = convertFrame(job, setup.config);
  if (setup.config.input.probability != ProbabilitySource::kGeometric) return frame;
  if (!geometric) throw std::logic_error("input.probability geometric needs a segmenter");
  naming("geometric segmentation",
         [&] { stocs::setGeometricProbabilities(frame, jobObjects(job, setup), *geometric); });
  return frame;
}

FrameResult detectJob(const EstimationJob& job, const EstimationSetup& setup,
                      stocs::GeometricSegmenter* geometric) {
  const stocs::Frame frame = estimationFrame(job, setup, geometric);
  FrameResult result;
  result.header = job.frame.header();
  std::vector<stocs::ObjectResult> estimates =
      stocs::estimateFrame(frame, jobObjects(job, setup), jobParams(job, setup.config));
  for (size_t k = 0; k < estimates.size(); ++k) {
    result.objects.push_back({job.objects[k], std::move(estimates[k].estimate), {}});
  }
  return result;
}

FrameResult trackJob(const EstimationJob& job, const std::shared_ptr<const EstimationSetup>& setup,
                     stocs::StreamTracker& tracker, stocs::GeometricSegmenter* geometric) {
  auto frame = std::make_shared<const stocs::Frame>(estimationFrame(job, *setup, geometric));
  FrameResult result;
  result.header = job.frame.header();
  std::optional<double> previous_input;
  if (job.previous_input) previous_input = job.previous_input->toSec();
  stocs::FrameTracking tracked =
      tracker.track(std::move(frame), jobObjects(job, *setup), jobParams(job, setup->config),
                    result.header.stamp.toSec(), previous_input, setup);
  for (size_t k = 0; k < tracked.objects.size(); ++k) {
    stocs::TrackedObject& t = tracked.objects[k];
    result.objects.push_back({job.objects[k], std::move(t.result.estimate), std::move(t.states)});
  }
  result.tracking = tracked.counts;
  return result;
}

}  // namespace stocs_ros
