#include "stocs_ros/segmentation_node/segmentation_node.h"

#include <cv_bridge/cv_bridge.h>
#include <fmt/format.h>
#include <ros/names.h>
#include <sensor_msgs/image_encodings.h>

#include <boost/make_shared.hpp>
#include <chrono>
#include <filesystem>
#include <opencv2/core.hpp>

#include "stocs/util/error.h"
#include "stocs_ros/common/resource_path.h"
#include "stocs_ros/common/schema_params.h"

namespace stocs_ros {
using stocs::InputError;

namespace {

namespace enc = sensor_msgs::image_encodings;

stocs::SegmentationNetworkParams networkParams(const ros::NodeHandle& pnh) {
  stocs::SegmentationNetworkParams p;
  readSchemaParams(pnh, stocs::SegmentationNetworkParams::schema(), p);
  if (p.model.empty()) {
    throw InputError(fmt::format("parameter {} is not set", pnh.resolveName("model")));
  }
  if (p.channels.empty()) {
    throw InputError(
        fmt::format("parameter {} must name the object of each output channel "
                    "('-' for none)",
                    pnh.resolveName("channels")));
  }
  for (const std::string& name : p.channels) {  // each object's map is ~probability/<name>
    std::string error;
    if (name != "-" && !ros::names::validate(name, error)) {
      throw InputError(fmt::format("parameter {} names '{}', which is not a ROS topic name: {}",
                                   pnh.resolveName("channels"), name, error));
    }
  }
  p.model = resolveResourcePath(p.model, {}).string();
  return p;
}

/// The colour image as BGR (a view where it already is), or InputError naming the encoding.
cv::Mat colourImage(const sensor_msgs::ImageConstPtr& msg) {
  for (const std::string& e : {enc::BGR8, enc::RGB8, enc::BGRA8, enc::RGBA8}) {
    if (msg->encoding == e) {
      try {
        return cv_bridge::toCvShare(msg, enc::BGR8)->image;
      } catch (const cv_bridge::Exception& ex) {
        throw InputError(fmt::format("image: {}", ex.what()));
      }
    }
  }
  throw InputError(fmt::format("encoding: '{}' is not a colour image (bgr8, rgb8, bgra8, rgba8)",
                               msg->encoding));
}

/// The channels `channels` of the network's output maps, upsampled straight into a message's
/// buffer: no full-size image is copied on the way.
sensor_msgs::ImagePtr mapsMessage(const std_msgs::Header& header, const cv::Mat& maps,
                                  const std::vector<int>& channels, cv::Size size, int depth) {
  auto msg = boost::make_shared<sensor_msgs::Image>();
  msg->header = header;
  msg->height = size.height;
  msg->width = size.width;
  const int type = CV_MAKETYPE(depth, static_cast<int>(channels.size()));
  msg->encoding = fmt::format("{}C{}", depth == CV_8U ? "8U" : "32F", channels.size());
  msg->is_bigendian = false;
  msg->step = size.width * CV_ELEM_SIZE(type);
  msg->data.resize(static_cast<size_t>(msg->step) * size.height);
  cv::Mat view(size, type, msg->data.data(), msg->step);
  stocs::SegmentationNetwork::upsample(maps, channels, size, depth, view);
  return msg;
}

/// Whether `model` is the package's own network (models/segmenter.onnx, however it is named).
bool isPackageNetwork(const std::string& model) {
  std::error_code error;
  try {
    return std::filesystem::equivalent(
        model, resolveResourcePath("package://stocs_ros/models/segmenter.onnx", {}), error);
  } catch (const InputError&) {  // the package is not on ROS_PACKAGE_PATH: not its network
    return false;
  }
}

}  // namespace

SegmentationNode::SegmentationNode(ros::NodeHandle pnh)
    : pnh_(pnh), transport_(pnh), network_(networkParams(pnh)) {
  readSchemaParams(pnh_, SegmentationOutputParams::schema(), output_);
  const auto& channels = network_.params().channels;
  for (size_t c = 0; c < channels.size(); ++c) {
    if (channels[c] != "-") objects_.emplace_back(channels[c], static_cast<int>(c));
  }
  const auto connection = [this](const ros::SingleSubscriberPublisher&) { updateSubscription(); };
  multichannel_ = pnh_.advertise<sensor_msgs::Image>("probability", 2, connection, connection);
  // A handle on the namespace, so that remapping ~probability moves the per-object topics too.
  ros::NodeHandle probability_nh(pnh_, "probability");
  for (const auto& object : objects_) {
    per_object_.push_back(
        probability_nh.advertise<sensor_msgs::Image>(object.first, 2, connection, connection));
  }
  statistics_ = pnh_.advertise<diagnostic_msgs::DiagnosticArray>("statistics", 1, true);
  statistics_timer_ =
      pnh_.createTimer(ros::Duration(1.0), &SegmentationNode::publishStatistics, this);
  ROS_INFO("segmentation: %s, %zu objects; waiting for subscribers",
           network_.params().model.c_str(), objects_.size());
  // Issue 42: on real images the demo's network marks unrelated objects as its six, silently.
  if (isPackageNetwork(network_.params().model)) {
    std::string names;
    for (const auto& object : objects_) names += (names.empty() ? "" : ", ") + object.first;
    ROS_WARN(
        "segmentation: %s is the package's own network, trained on generated scenes of the "
        "project's %zu meshes (%s) only: it knows nothing else, and on real images it marks "
        "unrelated objects as these. For your objects, give the StoCS node input.probability: "
        "geometric (maps from the depth alone, no network; README \"Your own objects\"), or set "
        "~model and ~channels to a network of your own (scripts/train_segmenter.sh --models "
        "trains one on your meshes; models/README.md)",
        network_.params().model.c_str(), objects_.size(), names.c_str());
  }
}

void SegmentationNode::updateSubscription() {
  std::lock_guard<std::mutex> lock(mutex_);
  bool wanted = multichannel_.getNumSubscribers() > 0;
  for (const ros::Publisher& p : per_object_) wanted = wanted || p.getNumSubscribers() > 0;
  if (wanted && !image_) {
    image_ = transport_.subscribe("image", 2, &SegmentationNode::onImage, this);
  } else if (!wanted && image_) {
    image_.shutdown();
  }
}

void SegmentationNode::onImage(const sensor_msgs::ImageConstPtr& msg) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++received_;
  }
  try {
    const cv::Mat bgr = colourImage(msg);
    const auto start = std::chrono::steady_clock::now();
    const auto messages = mapsMessages(msg->header, network_.outputMaps(bgr), bgr.size());
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (const auto& [publisher, message] : messages) publisher->publish(message);
    std::lock_guard<std::mutex> lock(mutex_);
    ++segmented_;
    seconds_ += seconds;
  } catch (const InputError& e) {
    const std::string what = e.what();
    rejected(what.substr(0, what.find(':')), what);
  } catch (const std::exception& e) {
    rejected("internal error", e.what());
  }
}

std::vector<std::pair<ros::Publisher*, sensor_msgs::ImagePtr>> SegmentationNode::mapsMessages(
    const std_msgs::Header& header, const cv::Mat& maps, cv::Size size) {
  const int depth = output_.depth == SegmentationOutputParams::Depth::kByte ? CV_8U : CV_32F;
  std::vector<std::pair<ros::Publisher*, sensor_msgs::ImagePtr>> messages;
  if (multichannel_.getNumSubscribers() > 0) {
    std::vector<int> channels;
    for (const auto& object : objects_) channels.push_back(object.second);
    messages.emplace_back(&multichannel_, mapsMessage(header, maps, channels, size, depth));
  }
  for (size_t i = 0; i < objects_.size(); ++i) {
    if (per_object_[i].getNumSubscribers() > 0) {
      messages.emplace_back(&per_object_[i],
                            mapsMessage(header, maps, {objects_[i].second}, size, depth));
    }
  }
  return messages;
}

void SegmentationNode::rejected(const std::string& reason, const std::string& message) {
  ROS_ERROR_THROTTLE(5.0, "segmentation: image rejected: %s", message.c_str());
  std::lock_guard<std::mutex> lock(mutex_);
  ++rejected_[reason];
}

void SegmentationNode::publishStatistics(const ros::TimerEvent&) {
  diagnostic_msgs::DiagnosticStatus status;
  status.name = pnh_.getNamespace();
  status.hardware_id = network_.params().model;
  const auto add = [&status](const std::string& key, const std::string& value) {
    diagnostic_msgs::KeyValue kv;
    kv.key = key;
    kv.value = value;
    status.values.push_back(kv);
  };
  std::lock_guard<std::mutex> lock(mutex_);
  add("subscribed to the image", image_ ? "1" : "0");
  add("images received", std::to_string(received_));
  add("images segmented", std::to_string(segmented_));
  uint64_t rejected_total = 0;
  for (const auto& [reason, count] : rejected_) {
    add("images rejected: " + reason, std::to_string(count));
    rejected_total += count;
  }
  add("images rejected", std::to_string(rejected_total));
  add("mean segmentation time (s)",
      fmt::format("{:.4f}", segmented_ > 0 ? seconds_ / segmented_ : 0.0));
  status.level = rejected_total > 0 ? diagnostic_msgs::DiagnosticStatus::WARN
                                    : diagnostic_msgs::DiagnosticStatus::OK;
  diagnostic_msgs::DiagnosticArray array;
  array.header.stamp = ros::Time::now();
  array.status.push_back(status);
  statistics_.publish(array);
}

}  // namespace stocs_ros
