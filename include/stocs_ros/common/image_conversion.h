#pragma once
// sensor_msgs/Image to the OpenCV images the core takes: probability maps (one per object, or one
// multi-channel image with a channel per object), instance boundary maps and the colour image.
// Errors are stocs::InputError with the encoding or size at fault.

#include <sensor_msgs/Image.h>

#include <opencv2/core.hpp>
#include <vector>

namespace stocs_ros {

/// A view of the image's pixels (sharing its data; keep `msg` alive). Accepts mono8, mono16 and
/// the generic 8UC<n>, 16UC<n>, 32FC<n>, 64FC<n>; rejects colour, Bayer and signed encodings and
/// images whose step or data size do not fit their width and height.
cv::Mat imageView(const sensor_msgs::ImageConstPtr& msg);

/// Probability in [0, 1] (CV_32FC1): 32FC1 and 64FC1 as they are, mono16/16UC1 divided by
/// `uint16_scale`, mono8/8UC1 divided by 255.
cv::Mat probabilityFromImage(const sensor_msgs::ImageConstPtr& msg, double uint16_scale);

/// One CV_32FC1 probability image per channel of a `channels`-channel image (32FC<n>, 16UC<n>,
/// 8UC<n>), scaled as in probabilityFromImage.
std::vector<cv::Mat> probabilitiesFromChannels(const sensor_msgs::ImageConstPtr& msg,
                                               size_t channels, double uint16_scale);

/// The registered colour image as the core takes it (CV_8UC3 BGR, a copy) from rgb8, bgr8, rgba8,
/// bgra8 or their 16-bit forms (scaled to 8 bits); any other encoding, mono included (it holds no
/// colour evidence), is an InputError.
cv::Mat colourFromImage(const sensor_msgs::ImageConstPtr& msg);

/// Instance boundary map (CV_8UC1, >= 128 interior) from mono8/8UC1.
cv::Mat boundaryFromImage(const sensor_msgs::ImageConstPtr& msg);

}  // namespace stocs_ros
