#include "stocs_ros/common/segmentation_conversion.h"

#include <cv_bridge/cv_bridge.h>
#include <fmt/format.h>

#include <boost/make_shared.hpp>
#include <functional>

#include "stocs/util/error.h"
#include "stocs_ros/common/image_conversion.h"
#include "stocs_ros/common/input_naming.h"

namespace stocs_ros {
using stocs::InputError;

namespace {

/// Runs `convert` for every object of `objects`, each error prefixed with `what`.
std::vector<cv::Mat> perObject(const std::string& what, const std::vector<size_t>& objects,
                               const NodeConfig& config,
                               const std::function<cv::Mat(int class_id)>& convert) {
  std::vector<cv::Mat> out(config.objects.size());
  naming(what, [&] {
    for (size_t i : objects) out[i] = convert(config.classOf(i));
    return 0;
  });
  return out;
}

template <class Message>
const Message& required(const boost::shared_ptr<const Message>& msg, const std::string& what) {
  if (!msg) throw InputError(fmt::format("{}: none given for input.probability", what));
  return *msg;
}

}  // namespace

std::vector<stocs::InstanceMask> masksFromMsg(const InstanceMaskArrayConstPtr& msg) {
  std::vector<stocs::InstanceMask> masks;
  for (size_t i = 0; i < msg->masks.size(); ++i) {
    const InstanceMask& m = msg->masks[i];
    // An aliasing pointer: the mask's image, kept alive by the array message.
    const sensor_msgs::ImageConstPtr image(msg, &m.mask);
    try {
      masks.push_back({imageView(image), m.class_id, m.score});
    } catch (const InputError& e) {
      throw InputError(fmt::format("mask {} (class {}): {}", i, m.class_id, e.what()));
    }
  }
  return masks;
}

std::vector<stocs::BoxDetection> boxesFromMsg(const Detection2DArray& msg) {
  std::vector<stocs::BoxDetection> boxes;
  for (const Detection2D& d : msg.detections) {
    boxes.push_back({cv::Rect2f(d.x, d.y, d.width, d.height), d.class_id, d.score});
  }
  return boxes;
}

std::vector<cv::Mat> probabilitiesFromSegmentation(const SegmentationMessages& messages,
                                                   const std::vector<size_t>& objects,
                                                   const NodeConfig& config, cv::Size size) {
  const stocs::SegmentationInputParams& params = config.input.segmentation;
  switch (config.input.probability) {
    case ProbabilitySource::kLabels: {
      required(messages.labels, "label image");
      const cv::Mat labels = naming("label image", [&] { return imageView(messages.labels); });
      const cv::Mat confidence = naming("label confidence image", [&] {
        return messages.label_confidence ? imageView(messages.label_confidence) : cv::Mat();
      });
      return perObject("label image", objects, config, [&](int class_id) {
        return stocs::labelProbability(labels, confidence, class_id, params,
                                       config.input.uint16_scale);
      });
    }
    case ProbabilitySource::kMasks: {
      required(messages.masks, "instance masks");
      const std::vector<stocs::InstanceMask> masks =
          naming("instance masks", [&] { return masksFromMsg(messages.masks); });
      return perObject("instance masks", objects, config, [&](int class_id) {
        return stocs::maskProbability(masks, class_id, size, params);
      });
    }
    case ProbabilitySource::kBoxes: {
      const std::vector<stocs::BoxDetection> boxes =
          boxesFromMsg(required(messages.boxes, "boxes"));
      return perObject("boxes", objects, config, [&](int class_id) {
        return stocs::boxProbability(boxes, class_id, size, params);
      });
    }
    default:
      return std::vector<cv::Mat>(config.objects.size());
  }
}

sensor_msgs::ImagePtr labelsToMsg(const cv::Mat& labels, const std::map<int, int>& class_of) {
  cv::Mat out(labels.size(), CV_16UC1, cv::Scalar(0));
  for (const auto& [id, class_id] : class_of) out.setTo(class_id, labels == id);
  return cv_bridge::CvImage(std_msgs::Header(), "mono16", out).toImageMsg();
}

InstanceMaskArrayPtr masksToMsg(const std::vector<stocs::InstanceMask>& masks,
                                const std::map<int, int>& class_of) {
  auto msg = boost::make_shared<InstanceMaskArray>();
  for (const stocs::InstanceMask& m : masks) {
    const auto it = class_of.find(m.class_id);
    if (it == class_of.end()) continue;
    InstanceMask out;
    out.mask = *cv_bridge::CvImage(std_msgs::Header(), "mono8", m.mask).toImageMsg();
    out.class_id = it->second;
    out.score = m.score;
    msg->masks.push_back(std::move(out));
  }
  return msg;
}

Detection2DArrayPtr boxesToMsg(const std::vector<stocs::BoxDetection>& boxes,
                               const std::map<int, int>& class_of) {
  auto msg = boost::make_shared<Detection2DArray>();
  for (const stocs::BoxDetection& b : boxes) {
    const auto it = class_of.find(b.class_id);
    if (it == class_of.end()) continue;
    Detection2D d;
    d.class_id = it->second;
    d.score = b.score;
    d.x = b.box.x;
    d.y = b.box.y;
    d.width = b.box.width;
    d.height = b.box.height;
    msg->detections.push_back(d);
  }
  return msg;
}

}  // namespace stocs_ros
