#include "stocs_ros/frame_estimation.h"

#include <fmt/format.h>

#include <opencv2/core.hpp>

#include "stocs/util/error.h"
#include "stocs_ros/cloud_conversion.h"
#include "stocs_ros/image_conversion.h"

namespace stocs_ros {
using stocs::InputError;

namespace {

/// Runs `convert`, prefixing the message of any InputError with `what`.
template <class Convert>
auto naming(const std::string& what, Convert&& convert) {
  try {
    return convert();
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", what, e.what()));
  }
}

/// Probability images by object index (empty where the frame has none).
std::vector<cv::Mat> probabilities(const EstimationJob& job, const NodeConfig& config) {
  const FrameMessages& frame = job.frame;
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

FrameResult estimateFrame(const EstimationJob& job, const EstimationSetup& setup) {
  const FrameMessages& frame = job.frame;
  const NodeConfig& config = setup.config;
  // The intrinsics once per frame: every object's free-space check projects with them.
  stocs::OrganizedCloud cloud;
  stocs::CameraIntrinsics camera;
  if (frame.cloud) {
    cloud = naming("cloud", [&] { return cloudFromMsg(*frame.cloud); });
    camera = naming("cloud", [&] { return intrinsicsFromCloud(cloud); });
  } else {
    cloud =
        naming("depth image", [&] { return cloudFromDepthImage(frame.depth, *frame.camera_info); });
    camera = intrinsicsFromCameraInfo(*frame.camera_info);
  }
  const auto focal_px = static_cast<float>(camera.fx);
  const std::vector<cv::Mat> probability = probabilities(job, config);
  const cv::Mat boundary =
      frame.boundary ? naming("boundary image", [&] { return boundaryFromImage(frame.boundary); })
                     : cv::Mat();
  stocs::PipelineParams params = config.estimation;
  if (job.time_budget) params.stocs.time_budget = *job.time_budget;

  FrameResult result;
  result.header = frame.header();
  for (size_t i : job.objects) {
    const std::string what = fmt::format("object '{}'", config.objects[i].name);
    if (probability[i].empty()) throw InputError(what + ": the frame has no probability image");
    result.objects.push_back({i, naming(what, [&] {
                                return stocs::estimateObject(
                                    cloud, focal_px, probability[i], setup.models[i], params,
                                    boundary.empty() ? nullptr : &boundary, &camera);
                              })});
  }
  return result;
}

}  // namespace stocs_ros
