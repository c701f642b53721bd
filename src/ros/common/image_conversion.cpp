#include "stocs_ros/common/image_conversion.h"

#include <cv_bridge/cv_bridge.h>
#include <fmt/format.h>
#include <sensor_msgs/image_encodings.h>

#include <set>

#include "stocs/io/probability_image.h"
#include "stocs/util/error.h"

namespace stocs_ros {
namespace enc = sensor_msgs::image_encodings;
using stocs::InputError;

namespace {

constexpr char kProbabilityEncodings[] = "32FC1, mono16 (16UC1) or mono8 (8UC1)";

int pixelType(const std::string& encoding) {
  int type = -1;
  try {
    type = cv_bridge::getCvType(encoding);
  } catch (const cv_bridge::Exception&) {
  }
  const int depth = CV_MAT_DEPTH(type);
  if (type < 0 || enc::isColor(encoding) || enc::isBayer(encoding) || encoding == enc::YUV422 ||
      (depth != CV_8U && depth != CV_16U && depth != CV_32F && depth != CV_64F)) {
    throw InputError(fmt::format(
        "encoding '{}' does not hold class probabilities or boundaries (expected mono8, mono16, "
        "8UC<n>, 16UC<n>, 32FC<n> or 64FC<n>)",
        encoding));
  }
  return type;
}

}  // namespace

namespace {

/// Throws InputError unless the image is non-empty, its step a whole number of `type`'s channel
/// values and at least a row, and its data exactly step x height bytes: cv_bridge and cv::Mat throw
/// their own exceptions otherwise (found by fuzz_ros_image).
void checkLayout(const sensor_msgs::Image& msg, int type) {
  const size_t row_bytes = static_cast<size_t>(msg.width) * CV_ELEM_SIZE(type);
  if (msg.width == 0 || msg.height == 0) {
    throw InputError(fmt::format("image is empty ({}x{})", msg.width, msg.height));
  }
  if (msg.step % CV_ELEM_SIZE1(type) != 0) {
    throw InputError(fmt::format("image '{}' has step {}, not a multiple of its {}-byte values",
                                 msg.encoding, msg.step, CV_ELEM_SIZE1(type)));
  }
  if (msg.step < row_bytes || msg.data.size() != static_cast<size_t>(msg.step) * msg.height) {
    throw InputError(fmt::format(
        "image {}x{} '{}' has step {} and {} data bytes; it needs a step of at least {} and "
        "step x height data bytes",
        msg.width, msg.height, msg.encoding, msg.step, msg.data.size(), row_bytes));
  }
}

}  // namespace

cv::Mat imageView(const sensor_msgs::ImageConstPtr& msg) {
  checkLayout(*msg, pixelType(msg->encoding));
  return cv_bridge::toCvShare(msg)->image;
}

cv::Mat colourFromImage(const sensor_msgs::ImageConstPtr& msg) {
  static const std::set<std::string> kColourEncodings = {enc::RGB8,   enc::BGR8,  enc::RGBA8,
                                                         enc::BGRA8,  enc::RGB16, enc::BGR16,
                                                         enc::RGBA16, enc::BGRA16};
  if (!kColourEncodings.count(msg->encoding)) {
    throw InputError(fmt::format(
        "colour image has encoding '{}'; expected rgb8, bgr8, rgba8, bgra8 or their 16-bit forms",
        msg->encoding));
  }
  checkLayout(*msg, cv_bridge::getCvType(msg->encoding));
  return cv_bridge::toCvCopy(msg, enc::BGR8)->image;
}

cv::Mat probabilityFromImage(const sensor_msgs::ImageConstPtr& msg, double uint16_scale) {
  const cv::Mat view = imageView(msg);
  if (view.channels() != 1) {
    throw InputError(
        fmt::format("probability image has encoding '{}' with {} channels; expected {}",
                    msg->encoding, view.channels(), kProbabilityEncodings));
  }
  return stocs::toProbabilityImage(view, uint16_scale);
}

std::vector<cv::Mat> probabilitiesFromChannels(const sensor_msgs::ImageConstPtr& msg,
                                               size_t channels, double uint16_scale) {
  const cv::Mat view = imageView(msg);
  if (static_cast<size_t>(view.channels()) != channels) {
    throw InputError(fmt::format(
        "multi-channel probability image has encoding '{}' ({} channels); the config names {}",
        msg->encoding, view.channels(), channels));
  }
  std::vector<cv::Mat> split;
  cv::split(view, split);
  std::vector<cv::Mat> out;
  for (size_t c = 0; c < split.size(); ++c) {
    try {
      out.push_back(stocs::toProbabilityImage(split[c], uint16_scale));
    } catch (const InputError& e) {
      throw InputError(fmt::format("channel {}: {}", c, e.what()));
    }
  }
  return out;
}

cv::Mat boundaryFromImage(const sensor_msgs::ImageConstPtr& msg) {
  const cv::Mat view = imageView(msg);
  if (view.type() != CV_8UC1) {
    throw InputError(
        fmt::format("boundary image has encoding '{}'; expected mono8 (8UC1)", msg->encoding));
  }
  return view.clone();
}

}  // namespace stocs_ros
