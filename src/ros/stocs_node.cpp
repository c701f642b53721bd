#include "stocs_ros/stocs_node.h"

#include <fmt/format.h>

#include <diagnostic_msgs/DiagnosticArray.h>

#include <algorithm>
#include <boost/make_shared.hpp>

#include "stocs/util/error.h"
#include "stocs_ros/result_messages.h"

namespace stocs_ros {
using stocs::InputError;

namespace {

constexpr double kWarnPeriod = 5.0;        // seconds between repeats of one kind of warning
constexpr double kStatisticsPeriod = 1.0;  // seconds between ~statistics messages

std::string requireConfigParameter(const ros::NodeHandle& pnh) {
  std::string file;
  if (!pnh.getParam("config", file) || file.empty()) {
    throw InputError(
        fmt::format("parameter {}/config (the configuration file) is not set", pnh.getNamespace()));
  }
  return file;
}

/// Reload can change models and estimation parameters, not what the node subscribes to.
void checkSameInputs(const NodeConfig& now, const NodeConfig& fresh) {
  std::vector<std::string> names_now, names_fresh;
  for (const ObjectConfig& o : now.objects) names_now.push_back(o.name);
  for (const ObjectConfig& o : fresh.objects) names_fresh.push_back(o.name);
  const InputConfig &a = now.input, &b = fresh.input;
  if (names_now != names_fresh || a.depth != b.depth || a.probability != b.probability ||
      a.channels != b.channels || a.boundary != b.boundary || a.uint16_scale != b.uint16_scale ||
      a.labels != b.labels || a.label_confidence != b.label_confidence ||
      a.sync.tolerance != b.sync.tolerance || a.sync.queue_size != b.sync.queue_size ||
      a.sync.max_age != b.sync.max_age) {
    throw InputError(fmt::format(
        "{}: the object names or the input section changed; restart the node to apply that",
        fresh.file.string()));
  }
}

std::string describeOutcome(const FrameResult& result, const NodeConfig& config) {
  std::string missing;
  size_t found = 0;
  for (const ObjectOutcome& o : result.objects) {
    if (o.estimate.found) {
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
/// configured objects), or the segmentation input.probability names.
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
  return frame;
}

}  // namespace

StocsNode::StocsNode(ros::NodeHandle pnh)
    : pnh_(pnh),
      config_file_(requireConfigParameter(pnh)),
      dataset_(pnh.param<std::string>("dataset", "")),
      setup_(loadSetup()),
      output_(pnh_),
      service_spinner_(1, &service_queue_) {
  const NodeConfig& config = setup_->config;
  worker_ = std::make_unique<JobWorker<QueuedJob, FrameResult>>(
      [this](const QueuedJob& q) { return process(q); },
      [this](std::exception_ptr e) { onBackgroundError(e); });
  subscribeInputs();

  ros::NodeHandle service_nh(pnh_);
  service_nh.setCallbackQueue(&service_queue_);
  estimate_service_ = service_nh.advertiseService("estimate", &StocsNode::onEstimate, this);
  reload_service_ = service_nh.advertiseService("reload", &StocsNode::onReload, this);
  service_spinner_.start();
  statistics_timer_ =
      pnh_.createWallTimer(ros::WallDuration(kStatisticsPeriod),
                           [this](const ros::WallTimerEvent&) { publishStatistics(); });
  ROS_INFO("stocs: %zu objects (%s) from %s; waiting for %zu synchronized inputs",
           config.objects.size(), config.objectNames().c_str(), config_file_.c_str(),
           inputs_.size());
}

StocsNode::~StocsNode() {
  // Stop every source of new jobs, then the worker, so that the final counts are complete.
  statistics_timer_.stop();
  for (ros::Subscriber& s : subscribers_) s.shutdown();
  service_spinner_.stop();
  estimate_service_.shutdown();
  reload_service_.shutdown();
  worker_.reset();
  ROS_INFO("stocs: at shutdown: %s", statistics_->summary().c_str());
}

std::shared_ptr<const EstimationSetup> StocsNode::loadSetup() const {
  return EstimationSetup::load(config_file_, dataset_,
                               [](const std::string& line) { ROS_INFO("%s", line.c_str()); });
}

std::shared_ptr<const EstimationSetup> StocsNode::setup() const {
  std::lock_guard<std::mutex> lock(setup_mutex_);
  return setup_;
}

void StocsNode::subscribeInputs() {
  const NodeConfig& config = setup_->config;
  // Per-object topics are resolved in a child handle so that remapping ~probability moves them all:
  // roscpp remaps node handle namespaces, not name prefixes.
  const ros::NodeHandle probability_nh(pnh_, "probability");
  const auto add = [&](const std::string& topic, InputKind kind, size_t object = 0) {
    inputs_.push_back({kind, object,
                       kind == InputKind::kProbability ? probability_nh.resolveName(topic)
                                                       : pnh_.resolveName(topic)});
  };
  if (config.input.depth == DepthSource::kCloud) {
    add("cloud", InputKind::kCloud);
  } else {
    add("depth", InputKind::kDepth);
    add("camera_info", InputKind::kCameraInfo);
  }
  switch (config.input.probability) {
    case ProbabilitySource::kMultichannel:
      add("probability", InputKind::kMultichannel);
      break;
    case ProbabilitySource::kLabels:
      add("labels", InputKind::kLabels);
      if (config.input.label_confidence) add("label_confidence", InputKind::kLabelConfidence);
      break;
    case ProbabilitySource::kMasks:
      add("masks", InputKind::kMasks);
      break;
    case ProbabilitySource::kBoxes:
      add("boxes", InputKind::kBoxes);
      break;
    case ProbabilitySource::kPerObject:
      for (size_t i = 0; i < config.objects.size(); ++i) {
        add(config.objects[i].name, InputKind::kProbability, i);
      }
  }
  if (config.input.boundary) add("boundary", InputKind::kBoundary);
  // Before the first subscription: with a multi-threaded nodelet manager, callbacks may start at
  // once.
  sync_ = std::make_unique<StampSynchronizer<InputMessage>>(inputs_.size(), config.input.sync);
  std::vector<std::string> topics;
  for (const Input& in : inputs_) topics.push_back(in.topic);
  statistics_ = std::make_unique<NodeStatistics>(std::move(topics));
  statistics_pub_ = pnh_.advertise<diagnostic_msgs::DiagnosticArray>("statistics", 1, true);

  const int queue = config.input.sync.queue_size;
  for (size_t i = 0; i < inputs_.size(); ++i) {
    switch (inputs_[i].kind) {
      case InputKind::kCloud:
        subscribe<sensor_msgs::PointCloud2>(i, queue);
        break;
      case InputKind::kCameraInfo:
        subscribe<sensor_msgs::CameraInfo>(i, queue);
        break;
      case InputKind::kMasks:
        subscribe<InstanceMaskArray>(i, queue);
        break;
      case InputKind::kBoxes:
        subscribe<Detection2DArray>(i, queue);
        break;
      default:
        subscribe<sensor_msgs::Image>(i, queue);
    }
  }
}

template <class Message>
void StocsNode::subscribe(size_t input, int queue_size) {
  const boost::function<void(const boost::shared_ptr<const Message>&)> callback =
      [this, input](const boost::shared_ptr<const Message>& msg) {
        onMessage(input, msg->header.stamp, msg);
      };
  subscribers_.push_back(pnh_.subscribe<Message>(inputs_[input].topic, queue_size, callback));
}

void StocsNode::onMessage(size_t input, const ros::Time& stamp, InputMessage message) {
  statistics_->received(input);
  const std::shared_ptr<const EstimationSetup> current = setup();
  std::vector<DroppedMessage> dropped;
  std::optional<QueuedJob> job;
  {
    std::lock_guard<std::mutex> lock(sync_mutex_);
    const uint64_t jumps_before = sync_->timeJumps();
    auto match = sync_->add(input, stamp, std::move(message), dropped);
    if (sync_->timeJumps() > jumps_before) onTimeJump(input, stamp);
    statistics_->dropped(dropped);
    if (!dropped.empty()) {
      const DroppedMessage& d = dropped.back();
      ROS_WARN_THROTTLE(kWarnPeriod,
                        "stocs: dropped a message of %s (stamp %.3f): %s; dropped so far: %s",
                        inputs_[d.input].topic.c_str(), d.stamp.toSec(), toString(d.reason),
                        describeDropCounts(sync_->dropCounts()).c_str());
    }
    if (!match) return;
    statistics_->matched();
    latest_frame_ = toFrame(match->messages, current->config.objects.size());
    latest_timeline_ = sync_->timeJumps();
    const std::optional<ros::Time> previous = latest_stamp_;
    latest_stamp_ = match->stamp;
    if (!current->config.output.estimate_on_frames) {
      statistics_->kept();
      return;
    }
    job = QueuedJob{{*latest_frame_, {}, std::nullopt, previous}, current, false, latest_timeline_};
  }
  for (size_t i = 0; i < current->config.objects.size(); ++i) job->job.objects.push_back(i);
  if (worker_->offer(std::move(*job))) {
    statistics_->replaced();
    ROS_WARN_THROTTLE(kWarnPeriod,
                      "stocs: estimation is slower than the input; a newer frame replaced one "
                      "waiting (counts on ~statistics)");
  }
}

void StocsNode::onTimeJump(size_t input, const ros::Time& stamp) {
  statistics_->timeJumpedBack();
  ROS_WARN(
      "stocs: time went back: %s is stamped %.3f, at or before the last matched frame (a bag "
      "played in a loop, a restarted camera driver or simulator?); synchronizing anew from there",
      inputs_[input].topic.c_str(), stamp.toSec());
}

FrameMessages StocsNode::toFrame(std::vector<InputMessage>& messages, size_t objects) const {
  FrameMessages frame;
  frame.probabilities.resize(objects);
  for (size_t i = 0; i < inputs_.size(); ++i) {
    InputMessage& m = messages[i];
    switch (inputs_[i].kind) {
      case InputKind::kCloud:
        frame.cloud = std::get<sensor_msgs::PointCloud2ConstPtr>(m);
        break;
      case InputKind::kDepth:
        frame.depth = std::get<sensor_msgs::ImageConstPtr>(m);
        break;
      case InputKind::kCameraInfo:
        frame.camera_info = std::get<sensor_msgs::CameraInfoConstPtr>(m);
        break;
      case InputKind::kProbability:
        frame.probabilities[inputs_[i].object] = std::get<sensor_msgs::ImageConstPtr>(m);
        break;
      case InputKind::kMultichannel:
        frame.multichannel = std::get<sensor_msgs::ImageConstPtr>(m);
        break;
      case InputKind::kBoundary:
        frame.boundary = std::get<sensor_msgs::ImageConstPtr>(m);
        break;
      case InputKind::kLabels:
        frame.segmentation.labels = std::get<sensor_msgs::ImageConstPtr>(m);
        break;
      case InputKind::kLabelConfidence:
        frame.segmentation.label_confidence = std::get<sensor_msgs::ImageConstPtr>(m);
        break;
      case InputKind::kMasks:
        frame.segmentation.masks = std::get<InstanceMaskArrayConstPtr>(m);
        break;
      case InputKind::kBoxes:
        frame.segmentation.boxes = std::get<Detection2DArrayConstPtr>(m);
        break;
    }
  }
  return frame;
}

FrameResult StocsNode::track(const QueuedJob& queued) {
  if (!frame_tracker_ || tracked_setup_ != queued.setup) {
    frame_tracker_.emplace(queued.setup->config.tracking);  // a reload may change every object
    tracked_setup_ = queued.setup;
  }
  FrameResult result = trackFrame(queued.job, queued.setup, *frame_tracker_);
  if (const std::optional<std::string> error = frame_tracker_->takeDetectionError()) {
    ROS_ERROR_THROTTLE(kWarnPeriod, "stocs: background detection failed: %s", error->c_str());
  }
  return result;
}

FrameResult StocsNode::process(const QueuedJob& queued) {
  // ~estimate calls detect: a call on an older frame or on given inputs must not move the tracks.
  const bool tracking = !queued.requested && queued.setup->config.tracking.enabled;
  FrameResult result = tracking ? track(queued) : estimateFrame(queued.job, *queued.setup);
  for (ObjectOutcome& o : result.objects) {
    stocs::PoseEstimate& e = o.estimate;
    if (e.found) {
      e.pose = tracker_.track(o.object, e.pose, queued.setup->config.objects[o.object].symmetries);
    }
  }
  output_.publish(result, *queued.setup, queued.timeline);
  statistics_->poses(foundPoses(result).size(), rejectedPoses(result).size());
  if (result.tracking) statistics_->tracking(*result.tracking);
  if (!queued.requested) statistics_->estimated();
  return result;
}

void StocsNode::onBackgroundError(std::exception_ptr error) {
  statistics_->rejected(rejectionKind(error));
  try {
    std::rethrow_exception(error);
  } catch (const std::exception& e) {
    ROS_ERROR_THROTTLE(kWarnPeriod, "stocs: frame rejected: %s (counts on ~statistics)", e.what());
  }
}

void StocsNode::publishStatistics() {
  std::vector<size_t> queued(inputs_.size());
  {
    std::lock_guard<std::mutex> lock(sync_mutex_);
    for (size_t i = 0; i < queued.size(); ++i) queued[i] = sync_->queued(i);
  }
  diagnostic_msgs::DiagnosticArray msg;
  msg.header.stamp = ros::Time::now();
  msg.status.push_back(statistics_->status(pnh_.getNamespace(), queued));
  statistics_pub_.publish(msg);
}

std::future<FrameResult> StocsNode::requestEstimation(
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
    // Taken and queued under the synchronizer's lock: a frame matched between the two could start
    // first, publish a newer stamp, and this result would then be too old for the topics.
    std::lock_guard<std::mutex> lock(sync_mutex_);
    if (!latest_frame_) {
      throw InputError(
          "no synchronized input frame yet; publish the inputs or pass a cloud (or a depth image "
          "with its camera_info) and probabilities");
    }
    job.frame = *latest_frame_;
    return worker_->request({std::move(job), setup, true, latest_timeline_});
  }
  job.frame = requestFrame(request, job.objects, config);
  std::lock_guard<std::mutex> lock(sync_mutex_);
  return worker_->request({std::move(job), setup, true, sync_->timeJumps()});
}

bool StocsNode::onEstimate(Estimate::Request& request, Estimate::Response& response) {
  const std::shared_ptr<const EstimationSetup> current = setup();
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
  statistics_->serviceCall(response.success);
  return true;  // the outcome is in the response, so the caller sees the message
}

bool StocsNode::onReload(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  try {
    const std::shared_ptr<const EstimationSetup> fresh = loadSetup();
    checkSameInputs(setup()->config, fresh->config);
    {
      std::lock_guard<std::mutex> lock(setup_mutex_);
      setup_ = fresh;
    }
    response.success = true;
    response.message =
        fmt::format("reloaded {} objects from {}", fresh->config.objects.size(), config_file_);
  } catch (const InputError& e) {
    response.success = false;
    response.message = e.what();
  }
  ROS_INFO("stocs: ~reload: %s", response.message.c_str());
  return true;
}

}  // namespace stocs_ros
