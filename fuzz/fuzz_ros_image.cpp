// sensor_msgs/Image to probability, boundary, colour and depth images
// (src/ros/image_conversion.cpp, cloudFromDepthImage): every field and the data come from the input
// (layout in ros_message_layout.h); each conversion must return or throw InputError.
#include "fuzz_support.h"
#include "ros_message_layout.h"
#include "stocs_ros/common/cloud_conversion.h"
#include "stocs_ros/common/image_conversion.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using stocs::fuzz::tolerateInputError;
  stocs::fuzz::ByteReader in(data, size);
  const sensor_msgs::ImagePtr msg(new sensor_msgs::Image);
  msg->width = in.take<uint32_t>();
  msg->height = in.take<uint32_t>();
  msg->step = in.take<uint32_t>();
  msg->encoding = in.pick(stocs::fuzz::kImageEncodings);
  const size_t channels = in.take<uint8_t>();
  sensor_msgs::CameraInfo info;
  info.width = in.take<uint32_t>();
  info.height = in.take<uint32_t>();
  info.binning_x = in.take<uint32_t>();
  info.binning_y = in.take<uint32_t>();
  info.K[0] = in.take<double>();
  info.K[4] = in.take<double>();
  info.K[2] = in.take<double>();
  info.K[5] = in.take<double>();
  msg->data = in.rest();
  tolerateInputError([&] { stocs_ros::probabilityFromImage(msg, 10000.0); });
  tolerateInputError([&] { stocs_ros::probabilitiesFromChannels(msg, channels, 10000.0); });
  tolerateInputError([&] { stocs_ros::boundaryFromImage(msg); });
  tolerateInputError([&] { stocs_ros::colourFromImage(msg); });
  tolerateInputError([&] { stocs_ros::cloudFromDepthImage(msg, info); });
  return 0;
}
