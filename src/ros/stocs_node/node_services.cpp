#include "stocs_ros/stocs_node/node_services.h"

#include <fmt/format.h>

#include <algorithm>
#include <boost/make_shared.hpp>

#include "stocs/util/error.h"
#include "stocs_ros/stocs_node/result_messages.h"

namespace stocs_ros {
using stocs::InputError;

namespace {

std::string describeOutcome(const FrameResult& result, const NodeConfig& config) {
  std::string missing;
  size_t found = 0;
  for (const ObjectOutcome& o : result.objects) {
    if (o.estimate.found()) {
      ++found;
    } else {
      missing += (missing.empty() ? "" : ", ") + config.objects[o.object].name;
    }
  }
  std::string rejected;
  for (const FoundPose& f : rejectedPoses(result)) {
    rejected += fmt::format("{}{} ({})", rejected.empty() ? "" : ", ",
                            instanceName(config.objects[f.outcome->object].name, f.instance),
                            rejectionReason(f));
  }
  return fmt::format("{} of {} objects found{}{}", found, result.objects.size(),
                     missing.empty() ? "" : "; no pose for " + missing,
                     rejected.empty() ? "" : "; rejected: " + rejected);
}

/// Whether an optional message of an ~estimate request was filled in.
bool given(const sensor_msgs::PointCloud2& cloud) {
  return !cloud.data.empty() || cloud.width > 0;
}
bool given(const sensor_msgs::Image& image) {
  return !image.data.empty() || image.width > 0;
}
bool given(const sensor_msgs::CameraInfo& info) {
  return info.width > 0 || info.height > 0 ||
         std::any_of(info.K.begin(), info.K.end(), [](double k) { return k != 0; });
}

/// The segmentation of an ~estimate request for input.probability labels, masks or boxes (an
/// empty masks or boxes list: nothing detected).
SegmentationMessages requestSegmentation(Estimate::Request& request, const NodeConfig& config) {
  if (!request.probabilities.empty()) {
    throw InputError(
        "probabilities were given, but input.probability takes labels, masks or boxes; give "
        "those instead");
  }
  SegmentationMessages s;
  switch (config.input.probability) {
    case ProbabilitySource::kLabels:
      if (!given(request.labels)) {
        throw InputError("input.probability is labels, but no label image (labels) was given");
      }
      s.labels = boost::make_shared<sensor_msgs::Image>(std::move(request.labels));
      if (given(request.label_confidence)) {
        s.label_confidence =
            boost::make_shared<sensor_msgs::Image>(std::move(request.label_confidence));
      }
      break;
    case ProbabilitySource::kMasks:
      s.masks = boost::make_shared<InstanceMaskArray>(std::move(request.masks));
      break;
    default:
      s.boxes = boost::make_shared<Detection2DArray>(std::move(request.boxes));
  }
  return s;
}

/// The frame of an ~estimate request with explicit inputs: a cloud, or a depth image with its
/// camera_info, and one probability image per requested object (`objects`, indices into the
/// configured objects), or the segmentation input.probability names (none for geometric).
FrameMessages requestFrame(Estimate::Request& request, const std::vector<size_t>& objects,
                           const NodeConfig& config) {
  if (given(request.cloud) && given(request.depth)) {
    throw InputError("both a cloud and a depth image were given; pass one of them");
  }
  if (given(request.depth) && !given(request.camera_info)) {
    throw InputError("a depth image was given without its camera_info (the camera's intrinsics)");
  }
  FrameMessages frame;
  if (config.input.segmentationForm()) {
    frame.segmentation = requestSegmentation(request, config);
  } else if (config.input.probability == ProbabilitySource::kGeometric) {
    if (!request.probabilities.empty()) {
      throw InputError(
          "probabilities were given, but input.probability is geometric: the maps come from the "
          "depth alone; give none");
    }
  } else if (request.probabilities.size() != objects.size()) {
    throw InputError(
        fmt::format("{} probability images for {} objects; give one per object, in "
                    "the order of `objects`",
                    request.probabilities.size(), objects.size()));
  }
  if (given(request.cloud)) {
    frame.cloud = boost::make_shared<sensor_msgs::PointCloud2>(std::move(request.cloud));
  } else {
    frame.depth = boost::make_shared<sensor_msgs::Image>(std::move(request.depth));
    frame.camera_info = boost::make_shared<sensor_msgs::CameraInfo>(std::move(request.camera_info));
  }
  frame.probabilities.resize(config.objects.size());
  for (size_t k = 0; k < request.probabilities.size(); ++k) {
    frame.probabilities[objects[k]] =
        boost::make_shared<sensor_msgs::Image>(std::move(request.probabilities[k]));
  }
  if (given(request.boundary)) {
    frame.boundary = boost::make_shared<sensor_msgs::Image>(std::move(request.boundary));
  }
  if (given(request.colour)) {
    frame.colour = boost::make_shared<sensor_msgs::Image>(std::move(request.colour));
  }
  return frame;
}

}  // namespace

NodeServices::NodeServices(const ros::NodeHandle& pnh, SetupStore& setups, FrameInputs& inputs,
                           EstimationWorker& worker, NodeStatistics& statistics,
                           std::function<void()> on_reload)
    : setups_(setups),
      inputs_(inputs),
      worker_(worker),
      statistics_(statistics),
      on_reload_(std::move(on_reload)),
      spinner_(1, &queue_) {
  ros::NodeHandle nh(pnh);
  nh.setCallbackQueue(&queue_);
  estimate_ = nh.advertiseService("estimate", &NodeServices::onEstimate, this);
  reload_ = nh.advertiseService("reload", &NodeServices::onReload, this);
  spinner_.start();
}

void NodeServices::shutdown() {
  spinner_.stop();
  estimate_.shutdown();
  reload_.shutdown();
}

std::future<FrameResult> NodeServices::requestEstimation(
    Estimate::Request& request, const std::shared_ptr<const EstimationSetup>& setup) {
  const NodeConfig& config = setup->config;
  EstimationJob job;
  for (const std::string& name : request.objects) {
    const int i = config.objectIndex(name);
    if (i < 0) {
      throw InputError(
          fmt::format("unknown object '{}'; configured objects: {}", name, config.objectNames()));
    }
    job.objects.push_back(static_cast<size_t>(i));
  }
  if (job.objects.empty()) {
    for (size_t i = 0; i < config.objects.size(); ++i) job.objects.push_back(i);
  }
  if (!(request.time_budget >= 0)) {
    throw InputError(fmt::format("time_budget {} s is negative", request.time_budget));
  }
  if (request.time_budget > 0) job.time_budget = request.time_budget;

  if (given(request.camera_info) && !given(request.depth)) {
    throw InputError("a camera_info was given without a depth image");
  }
  if (!given(request.cloud) && !given(request.depth)) {
    if (!request.probabilities.empty()) {
      throw InputError("probabilities were given without a cloud or depth image");
    }
    if (given(request.labels) || !request.masks.masks.empty() ||
        !request.boxes.detections.empty()) {
      throw InputError("labels, masks or boxes were given without a cloud or depth image");
    }
    // Taken and queued under the inputs' lock: a frame matched between the two could start
    // first, publish a newer stamp, and this result would then be too old for the topics.
    return inputs_.withLatest([&](const MatchedFrame* latest, uint64_t) {
      if (!latest) {
        throw InputError(
            "no synchronized input frame yet; publish the inputs or pass a cloud (or a depth image "
            "with its camera_info) and probabilities");
      }
      job.frame = latest->frame;
      return worker_.request({std::move(job), setup, true, latest->timeline});
    });
  }
  job.frame = requestFrame(request, job.objects, config);
  return inputs_.withLatest([&](const MatchedFrame*, uint64_t time_jumps) {
    return worker_.request({std::move(job), setup, true, time_jumps});
  });
}

bool NodeServices::onEstimate(Estimate::Request& request, Estimate::Response& response) {
  const std::shared_ptr<const EstimationSetup> current = setups_.current();
  try {
    const FrameResult result = requestEstimation(request, current).get();
    response.result = toObjectPoseArray(result, *current);
    response.success = true;
    response.message = describeOutcome(result, current->config);
  } catch (const std::exception& e) {
    response.success = false;
    response.message = e.what();
    ROS_WARN("stocs: ~estimate failed: %s", e.what());
  }
  statistics_.serviceCall(response.success);
  return true;  // the outcome is in the response, so the caller sees the message
}

bool NodeServices::onReload(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  try {
    response.message = setups_.reload();
    response.success = true;
    on_reload_();
  } catch (const InputError& e) {
    response.success = false;
    response.message = e.what();
  }
  ROS_INFO("stocs: ~reload: %s", response.message.c_str());
  return true;
}

}  // namespace stocs_ros
