#include "stocs_ros/scene_publisher/scene_publisher.h"

#include <cv_bridge/cv_bridge.h>
#include <fmt/format.h>
#include <sensor_msgs/CameraInfo.h>
#include <tf2_eigen/tf2_eigen.h>

#include <algorithm>
#include <filesystem>
#include <opencv2/core.hpp>

#include "stocs/sim/sequence_info.h"
#include "stocs/util/error.h"
#include "stocs_ros/common/cloud_conversion.h"
#include "stocs_ros/common/instance_name.h"
#include "stocs_ros/common/schema_params.h"
#include "stocs_ros/common/segmentation_conversion.h"

namespace stocs_ros {
using stocs::InputError;

namespace {

/// The private parameters, the required ones set; throws stocs::InputError naming a bad one.
ScenePublisherParams readParams(const ros::NodeHandle& pnh) {
  ScenePublisherParams params;
  readSchemaParams(pnh, ScenePublisherParams::schema(), params);
  requireSet(pnh, "dataset", params.dataset);
  requireSet(pnh, "config", params.config);
  return params;
}

/// OpenCV depth and the ROS encoding of a probability image with `channels` channels.
std::pair<int, std::string> probabilityFormat(const std::string& encoding, size_t channels) {
  const std::string n = std::to_string(channels);
  if (encoding == "mono16") return {CV_16U, channels == 1 ? "mono16" : "16UC" + n};
  if (encoding == "mono8") return {CV_8U, channels == 1 ? "mono8" : "8UC" + n};
  return {CV_32F, "32FC" + n};
}

/// "labels", "masks" or "boxes": the config's segmentation input.
std::string segmentationForm(const NodeConfig& config) {
  switch (config.input.probability) {
    case ProbabilitySource::kLabels:
      return "labels";
    case ProbabilitySource::kMasks:
      return "masks";
    default:
      return "boxes";
  }
}

/// The probability maps `spec` (~probability_source) names, as `stocs estimate --prob` takes
/// them; simulated maps draw on the estimator's seed.
std::unique_ptr<stocs::ProbabilitySource> probabilitySource(std::string spec,
                                                            const stocs::BopDataset& dataset,
                                                            const NodeConfig& config) {
  // A segmentation input plays the frame's ground-truth detections unless a spec of its form is
  // given: "real" (the launch files' default) means the dataset's own data.
  if (config.input.segmentationForm() && !stocs::isSegmentationInputSpec(spec)) {
    spec = segmentationForm(config);
  }
  try {
    return stocs::makeProbabilitySource(spec, dataset, config.estimation.stocs.seed);
  } catch (const InputError& e) {
    throw InputError(fmt::format("parameter probability_source '{}': {}", spec, e.what()));
  }
}

/// Where a dataset has no rate of its own: two frames per `tracking.max_gap` when the node tracks
/// (4 Hz for the default 0.5 s), so that a frame a little late still continues the tracks; at
/// 1 Hz every gap ended them and the node's default, tracking, never engaged (issue 42). At least
/// 1 Hz, at most 100.
double fallbackRate(const stocs::TrackingParams& tracking) {
  if (!tracking.enabled) return 1.0;
  return std::clamp(2.0 / tracking.max_gap, 1.0, 100.0);
}

/// `rate` (~rate), or where it is 0 (the default) the rate of the played sequences (their
/// scene_events.json), else fallbackRate.
double playbackRate(double rate, const stocs::BopDataset& dataset, const std::vector<int>& scenes,
                    const stocs::TrackingParams& tracking) {
  if (rate == 0) rate = stocs::sequenceRate(dataset, scenes).value_or(fallbackRate(tracking));
  if (!(rate > 0 && rate <= 100)) {
    throw InputError(fmt::format("parameter rate {} Hz is outside (0, 100]", rate));
  }
  return rate;
}

sensor_msgs::CameraInfo cameraInfo(const stocs::CameraIntrinsics& k,
                                   const std_msgs::Header& header) {
  sensor_msgs::CameraInfo info;
  info.header = header;
  info.width = k.width;
  info.height = k.height;
  info.distortion_model = "plumb_bob";
  info.D.assign(5, 0.0);
  info.K = {k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.P = {k.fx, 0, k.cx, 0, 0, k.fy, k.cy, 0, 0, 0, 1, 0};
  return info;
}

}  // namespace

ScenePublisher::ScenePublisher(ros::NodeHandle pnh)
    : pnh_(pnh),
      params_(readParams(pnh)),
      dataset_(params_.dataset, params_.split),
      config_(loadNodeConfig(params_.config, dataset_.root())),
      probability_source_(probabilitySource(params_.probability_source, dataset_, config_)) {
  std::vector<int> scenes = params_.scenes;
  const std::vector<int>& images = params_.images;
  if (scenes.empty()) scenes = dataset_.sceneIds();
  for (int scene : scenes) {
    if (!std::filesystem::is_directory(dataset_.sceneDir(scene))) {
      throw InputError(fmt::format("{}: scene {} does not exist", dataset_.root().string(), scene));
    }
    cameras_[scene] = dataset_.sceneCameras(scene);
    if (std::filesystem::exists(dataset_.sceneDir(scene) / "scene_gt.json")) {
      ground_truth_[scene] = dataset_.sceneGroundTruth(scene);
    }
    for (const auto& entry : cameras_[scene]) {
      if (images.empty() || std::count(images.begin(), images.end(), entry.first)) {
        frames_.push_back({scene, entry.first});
      }
    }
  }
  if (frames_.empty()) {
    throw InputError(fmt::format("{}: no frame matches the selected scenes and images",
                                 dataset_.root().string()));
  }
  for (const ObjectConfig& o : config_.objects) object_ids_.push_back(o.id);
  const double rate = playbackRate(params_.rate, dataset_, scenes, config_.tracking);
  cache_frames_ = params_.cache || params_.preload;
  cache_.resize(frames_.size());
  if (params_.preload) preload();

  cloud_ = pnh_.advertise<sensor_msgs::PointCloud2>("cloud", 2);
  depth_ = pnh_.advertise<sensor_msgs::Image>("depth", 2);
  camera_info_ = pnh_.advertise<sensor_msgs::CameraInfo>("camera_info", 2);
  rgb_ = pnh_.advertise<sensor_msgs::Image>("rgb", 2);
  boundary_ = pnh_.advertise<sensor_msgs::Image>("boundary", 2);
  truth_markers_ = pnh_.advertise<visualization_msgs::MarkerArray>("ground_truth_markers", 2);
  if (config_.input.segmentationForm()) {
    advertiseSegmentation();
  } else if (config_.input.probability == ProbabilitySource::kMultichannel) {
    multichannel_ = pnh_.advertise<sensor_msgs::Image>("probability", 2);
  } else if (config_.input.probability == ProbabilitySource::kPerObject) {
    // In a child handle, so that remapping ~probability moves every per-object topic.
    ros::NodeHandle probability_nh(pnh_, "probability");
    for (const ObjectConfig& o : config_.objects) {
      probabilities_.push_back(probability_nh.advertise<sensor_msgs::Image>(o.name, 2));
    }
  }
  loadNext();
  timer_ = pnh_.createTimer(ros::Duration(1.0 / rate), &ScenePublisher::onTimer, this);
  ROS_INFO("scene_publisher: %zu frames of %s at %.2f Hz%s, probability maps '%s'", frames_.size(),
           dataset_.root().c_str(), rate, params_.loop ? ", looping" : "",
           probability_source_->spec().c_str());
}

void ScenePublisher::onTimer(const ros::TimerEvent&) {
  if (!pending_.valid()) {
    timer_.stop();
    ROS_INFO("scene_publisher: all %zu frames published", frames_.size());
    return;
  }
  const FrameRef ref = pending_ref_;
  try {
    const std::shared_ptr<const BopFrame> loaded = pending_.get();
    const BopFrame& frame = *loaded;
    loadNext();  // while this one is published and until the next tick
    warnOfMissingMap(ref, frame);
    publish(ref, frame);
  } catch (const InputError& e) {
    if (!pending_.valid()) loadNext();
    ROS_ERROR_THROTTLE(5.0, "scene_publisher: scene %d image %d skipped: %s", ref.scene, ref.image,
                       e.what());
  }
}

void ScenePublisher::loadNext() {
  if (next_ == frames_.size()) {
    if (!params_.loop) return;
    next_ = 0;
    // Stamps are the time of publishing, so they keep increasing; the scene itself starts over.
    // Throttled: a five-frame sequence at 30 Hz starts over six times a second.
    ++pass_;  // not inside the macro, which skips its arguments when it throttles
    ROS_INFO_THROTTLE(
        5.0, "scene_publisher: pass %d: back to scene %d image %d (stamps keep increasing)", pass_,
        frames_[0].scene, frames_[0].image);
  }
  const size_t index = next_++;
  pending_ref_ = frames_[index];
  if (cache_[index]) {
    std::promise<std::shared_ptr<const BopFrame>> cached;
    cached.set_value(cache_[index]);
    pending_ = cached.get_future();
    return;
  }
  // One load at a time: the probability source is not for use from several threads at once.
  pending_ = std::async(std::launch::async, [this, index] { return load(index); });
}

std::shared_ptr<const BopFrame> ScenePublisher::load(size_t index) {
  const FrameRef& ref = frames_[index];
  // A node that segments the depth itself (input.probability geometric) gets no maps.
  const bool maps = config_.input.probability != ProbabilitySource::kGeometric;
  auto frame = std::make_shared<const BopFrame>(
      loadBopFrame(dataset_, ref.scene, ref.image, cameras_.at(ref.scene).at(ref.image),
                   maps ? object_ids_ : std::vector<int>{}, *probability_source_));
  if (cache_frames_) cache_[index] = frame;
  return frame;
}

void ScenePublisher::preload() {
  ROS_INFO("scene_publisher: decoding all %zu frames before publishing (~preload)", frames_.size());
  for (size_t index = 0; index < frames_.size(); ++index) {
    try {
      load(index);
    } catch (const InputError& e) {  // read again, and reported, when its turn comes
      ROS_ERROR_THROTTLE(5.0, "scene_publisher: scene %d image %d: %s", frames_[index].scene,
                         frames_[index].image, e.what());
    }
  }
}

namespace {

/// A Send that stamps `message` (a shared pointer) and publishes it on `publisher`.
template <class MessagePtr>
std::function<void(const ros::Time&)> sending(ros::Publisher& publisher, MessagePtr message) {
  return [&publisher, message](const ros::Time& stamp) {
    message->header.stamp = stamp;
    publisher.publish(message);
  };
}

}  // namespace

void ScenePublisher::publish(const FrameRef& ref, const BopFrame& frame) {
  std_msgs::Header header;
  header.frame_id = params_.frame_id;
  std::vector<Send> sends;
  auto cloud = boost::make_shared<sensor_msgs::PointCloud2>(cloudToMsg(frame.cloud, frame.bgr));
  cloud->header = header;
  sends.push_back(sending(cloud_, cloud));
  sends.push_back(sending(depth_, cv_bridge::CvImage(header, "32FC1", frame.depth).toImageMsg()));
  sends.push_back(sending(
      camera_info_, boost::make_shared<sensor_msgs::CameraInfo>(cameraInfo(frame.camera, header))));
  if (!frame.bgr.empty()) {
    sends.push_back(sending(rgb_, cv_bridge::CvImage(header, "bgr8", frame.bgr).toImageMsg()));
  }
  if (segmentation_) {
    addSegmentation(ref, header, sends);
  } else {
    addProbabilities(frame, header, sends);
  }
  if (params_.boundary) {
    // A frame without a map gets an all-interior one, so that a node waiting for boundaries still
    // receives complete frames.
    const cv::Mat boundary = frame.boundary.empty()
                                 ? cv::Mat(frame.depth.size(), CV_8UC1, cv::Scalar(255))
                                 : frame.boundary;
    sends.push_back(sending(boundary_, cv_bridge::CvImage(header, "mono8", boundary).toImageMsg()));
  }
  header.stamp = ros::Time::now();
  for (const Send& send : sends) send(header.stamp);
  publishGroundTruth(ref, header);
}

void ScenePublisher::addProbabilities(const BopFrame& frame, const std_msgs::Header& header,
                                      std::vector<Send>& sends) {
  const bool multichannel = config_.input.probability == ProbabilitySource::kMultichannel;
  const auto [depth, encoding] = probabilityFormat(
      params_.probability_encoding, multichannel ? config_.input.channels.size() : 1);
  const double scale = depth == CV_16U ? config_.input.uint16_scale : depth == CV_8U ? 255.0 : 1.0;
  std::vector<cv::Mat> encoded;
  for (const cv::Mat& p : frame.probabilities) {
    cv::Mat e;
    p.convertTo(e, depth, scale);  // rounds: a mono16 map from a BOP file comes back exactly
    encoded.push_back(e);
  }
  if (!multichannel) {
    for (size_t i = 0; i < encoded.size(); ++i) {
      sends.push_back(sending(probabilities_[i],
                              cv_bridge::CvImage(header, encoding, encoded[i]).toImageMsg()));
    }
    return;
  }
  std::vector<cv::Mat> channels;
  for (const std::string& name : config_.input.channels) {
    const int i = config_.objectIndex(name);
    channels.push_back(i >= 0 ? encoded[i] : cv::Mat::zeros(frame.depth.size(), depth));
  }
  cv::Mat merged;
  cv::merge(channels, merged);
  sends.push_back(
      sending(multichannel_, cv_bridge::CvImage(header, encoding, merged).toImageMsg()));
}

void ScenePublisher::advertiseSegmentation() {
  const std::string spec = probability_source_->spec();
  if (!stocs::isSegmentationInputSpec(spec) || spec.rfind(segmentationForm(config_), 0) != 0) {
    throw InputError(fmt::format(
        "parameter probability_source '{}' does not give input.probability '{}'; use {}, "
        "{}:perturbed "
        "or another spec of that form",
        spec, segmentationForm(config_), segmentationForm(config_), segmentationForm(config_)));
  }
  segmentation_ = std::make_unique<stocs::SegmentationInputSource>(
      spec, dataset_, config_.estimation.stocs.seed, config_.input.segmentation);
  for (size_t i = 0; i < config_.objects.size(); ++i) {
    class_of_[config_.objects[i].id] = config_.classOf(i);
  }
  switch (config_.input.probability) {
    case ProbabilitySource::kLabels:
      segmentation_pub_ = pnh_.advertise<sensor_msgs::Image>("labels", 2);
      break;
    case ProbabilitySource::kMasks:
      segmentation_pub_ = pnh_.advertise<InstanceMaskArray>("masks", 2);
      break;
    default:
      segmentation_pub_ = pnh_.advertise<Detection2DArray>("boxes", 2);
  }
}

void ScenePublisher::addSegmentation(const FrameRef& ref, const std_msgs::Header& header,
                                     std::vector<Send>& sends) {
  const auto send = [&](auto msg) {
    msg->header = header;
    sends.push_back(sending(segmentation_pub_, msg));
  };
  switch (config_.input.probability) {
    case ProbabilitySource::kLabels:
      send(labelsToMsg(segmentation_->labels(ref.scene, ref.image), class_of_));
      break;
    case ProbabilitySource::kMasks:
      send(masksToMsg(segmentation_->masks(ref.scene, ref.image, object_ids_), class_of_));
      break;
    default:
      send(boxesToMsg(segmentation_->boxes(ref.scene, ref.image), class_of_));
  }
}

void ScenePublisher::publishGroundTruth(const FrameRef& ref, const std_msgs::Header& header) {
  const auto scene = ground_truth_.find(ref.scene);
  if (scene == ground_truth_.end()) return;
  const auto image = scene->second.find(ref.image);
  if (image == scene->second.end()) return;
  std::map<std::string, int> instances;
  std::vector<geometry_msgs::TransformStamped> transforms;
  std::vector<TruthPose> truth;
  for (const stocs::BopGtInstance& g : image->second) {
    const std::string name = objectName(g.obj_id);
    const int k = instances[name]++;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::Quaterniond(g.R).normalized().toRotationMatrix();
    pose.translation() = g.t_mm / 1000.0;
    geometry_msgs::TransformStamped t = tf2::eigenToTransform(pose);
    t.header = header;
    t.child_frame_id = "gt_" + instanceName(name, k);
    transforms.push_back(t);
    truth.push_back({name, static_cast<size_t>(k), pose});
  }
  tf_.sendTransform(transforms);
  if (truth_markers_.getNumSubscribers() > 0) {
    truth_markers_.publish(truth_marker_builder_.build(truth, header));
  }
}

void ScenePublisher::warnOfMissingMap(const FrameRef& ref, const BopFrame& frame) {
  if (warned_of_missing_map_) return;
  for (int id : frame.objects_without_map) {
    if (!mayShow(ref, id)) continue;
    ROS_WARN(
        "scene_publisher: %s has no probability map (prob/) for object '%s' (id %d) in scene %d "
        "image %d: its probability image is all zero and the estimator finds nothing there. "
        "To simulate maps from the ground truth, set the parameter ~probability_source (launch "
        "argument probability_source:=) to sim:PRESET, e.g. sim:mild; valid: %s. (Warned once.)",
        dataset_.root().c_str(), objectName(id).c_str(), id, ref.scene, ref.image,
        stocs::probabilitySourceHelp().c_str());
    warned_of_missing_map_ = true;
    return;
  }
}

bool ScenePublisher::mayShow(const FrameRef& ref, int obj_id) const {
  const auto scene = ground_truth_.find(ref.scene);
  if (scene == ground_truth_.end()) return true;
  const auto image = scene->second.find(ref.image);
  return image != scene->second.end() &&
         std::any_of(image->second.begin(), image->second.end(),
                     [obj_id](const stocs::BopGtInstance& g) { return g.obj_id == obj_id; });
}

std::string ScenePublisher::objectName(int obj_id) const {
  for (const ObjectConfig& o : config_.objects) {
    if (o.id == obj_id) return o.name;
  }
  return "obj_" + std::to_string(obj_id);
}

}  // namespace stocs_ros
