#include "stocs_ros/stocs_node/frame_inputs.h"

namespace stocs_ros {
FrameInputs::FrameInputs(ros::NodeHandle pnh, const NodeConfig& config)
    : pnh_(std::move(pnh)),
      objects_(config.objects.size()),
      queue_size_(config.input.sync.queue_size) {
  if (config.input.depth == DepthSource::kCloud) {
    add("cloud", Kind::kCloud);
  } else {
    add("depth", Kind::kDepth);
    add("camera_info", Kind::kCameraInfo);
  }
  switch (config.input.probability) {
    case ProbabilitySource::kMultichannel:
      add("probability", Kind::kMultichannel);
      break;
    case ProbabilitySource::kLabels:
      add("labels", Kind::kLabels);
      if (config.input.label_confidence) add("label_confidence", Kind::kLabelConfidence);
      break;
    case ProbabilitySource::kMasks:
      add("masks", Kind::kMasks);
      break;
    case ProbabilitySource::kBoxes:
      add("boxes", Kind::kBoxes);
      break;
    case ProbabilitySource::kPerObject:
      for (size_t i = 0; i < config.objects.size(); ++i) {
        add(config.objects[i].name, Kind::kProbability, i);
      }
      break;
    case ProbabilitySource::kGeometric:
      break;  // the maps come from the depth alone
  }
  if (config.input.boundary) add("boundary", Kind::kBoundary);
  if (config.input.colour) add("rgb", Kind::kColour);
  sync_ = std::make_unique<StampSynchronizer<Message>>(inputs_.size(), config.input.sync);
}

void FrameInputs::add(const std::string& topic, Kind kind, size_t object) {
  // Per-object topics are resolved in a child handle so that remapping ~probability moves them all:
  // roscpp remaps node handle namespaces, not name prefixes.
  const std::string resolved = kind == Kind::kProbability
                                   ? ros::NodeHandle(pnh_, "probability").resolveName(topic)
                                   : pnh_.resolveName(topic);
  inputs_.push_back({kind, object, resolved});
}

std::vector<std::string> FrameInputs::topics() const {
  std::vector<std::string> topics;
  for (const Input& in : inputs_) topics.push_back(in.topic);
  return topics;
}

void FrameInputs::subscribe(NodeStatistics& statistics,
                            std::function<void(MatchedFrame)> on_frame) {
  statistics_ = &statistics;
  on_frame_ = std::move(on_frame);
  for (size_t i = 0; i < inputs_.size(); ++i) {
    switch (inputs_[i].kind) {
      case Kind::kCloud:
        subscribeTo<sensor_msgs::PointCloud2>(i, queue_size_);
        break;
      case Kind::kCameraInfo:
        subscribeTo<sensor_msgs::CameraInfo>(i, queue_size_);
        break;
      case Kind::kMasks:
        subscribeTo<InstanceMaskArray>(i, queue_size_);
        break;
      case Kind::kBoxes:
        subscribeTo<Detection2DArray>(i, queue_size_);
        break;
      default:
        subscribeTo<sensor_msgs::Image>(i, queue_size_);
    }
  }
}

void FrameInputs::shutdown() {
  for (ros::Subscriber& s : subscribers_) s.shutdown();
}

template <class M>
void FrameInputs::subscribeTo(size_t input, int queue_size) {
  const boost::function<void(const boost::shared_ptr<const M>&)> callback =
      [this, input](const boost::shared_ptr<const M>& msg) {
        onMessage(input, msg->header.stamp, msg);
      };
  subscribers_.push_back(pnh_.subscribe<M>(inputs_[input].topic, queue_size, callback));
}

void FrameInputs::onMessage(size_t input, const ros::Time& stamp, Message message) {
  statistics_->received(input);
  MatchedFrame matched;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<DroppedMessage> dropped;
    const uint64_t jumps_before = sync_->timeJumps();
    auto match = sync_->add(input, stamp, std::move(message), dropped);
    if (sync_->timeJumps() > jumps_before) onTimeJump(input, stamp);
    statistics_->dropped(dropped);
    logDropped(dropped);
    if (!match) return;
    statistics_->matched();
    const std::optional<ros::Time> previous =
        latest_ ? std::optional<ros::Time>(latest_->stamp) : std::nullopt;
    matched = MatchedFrame{toFrame(match->messages), match->stamp, sync_->timeJumps(), previous};
    latest_ = matched;
  }
  on_frame_(std::move(matched));
}

void FrameInputs::logDropped(const std::vector<DroppedMessage>& dropped) const {
  if (dropped.empty()) return;
  const DroppedMessage& d = dropped.back();
  ROS_WARN_THROTTLE(kWarnPeriod,
                    "stocs: dropped a message of %s (stamp %.3f): %s; dropped so far: %s",
                    inputs_[d.input].topic.c_str(), d.stamp.toSec(), toString(d.reason),
                    describeDropCounts(sync_->dropCounts()).c_str());
}

void FrameInputs::onTimeJump(size_t input, const ros::Time& stamp) {
  statistics_->timeJumpedBack();
  ROS_WARN(
      "stocs: time went back: %s is stamped %.3f, at or before the last matched frame (a bag "
      "played in a loop, a restarted camera driver or simulator?); synchronizing anew from there",
      inputs_[input].topic.c_str(), stamp.toSec());
}

std::vector<size_t> FrameInputs::queued() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<size_t> queued(inputs_.size());
  for (size_t i = 0; i < queued.size(); ++i) queued[i] = sync_->queued(i);
  return queued;
}

FrameMessages FrameInputs::toFrame(std::vector<Message>& messages) const {
  FrameMessages frame;
  frame.probabilities.resize(objects_);
  for (size_t i = 0; i < inputs_.size(); ++i) {
    Message& m = messages[i];
    switch (inputs_[i].kind) {
      case Kind::kCloud:
        frame.cloud = std::get<sensor_msgs::PointCloud2ConstPtr>(m);
        break;
      case Kind::kDepth:
        frame.depth = std::get<sensor_msgs::ImageConstPtr>(m);
        break;
      case Kind::kCameraInfo:
        frame.camera_info = std::get<sensor_msgs::CameraInfoConstPtr>(m);
        break;
      case Kind::kProbability:
        frame.probabilities[inputs_[i].object] = std::get<sensor_msgs::ImageConstPtr>(m);
        break;
      case Kind::kMultichannel:
        frame.multichannel = std::get<sensor_msgs::ImageConstPtr>(m);
        break;
      case Kind::kBoundary:
        frame.boundary = std::get<sensor_msgs::ImageConstPtr>(m);
        break;
      case Kind::kColour:
        frame.colour = std::get<sensor_msgs::ImageConstPtr>(m);
        break;
      case Kind::kLabels:
        frame.segmentation.labels = std::get<sensor_msgs::ImageConstPtr>(m);
        break;
      case Kind::kLabelConfidence:
        frame.segmentation.label_confidence = std::get<sensor_msgs::ImageConstPtr>(m);
        break;
      case Kind::kMasks:
        frame.segmentation.masks = std::get<InstanceMaskArrayConstPtr>(m);
        break;
      case Kind::kBoxes:
        frame.segmentation.boxes = std::get<Detection2DArrayConstPtr>(m);
        break;
    }
  }
  return frame;
}

}  // namespace stocs_ros
