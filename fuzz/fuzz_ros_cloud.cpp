// sensor_msgs/PointCloud2 to the core's organized cloud (src/ros/cloud_conversion.cpp): every
// header field and the data come from the input (layout in ros_message_layout.h); the conversion
// must return a cloud of width x height points (and a colour image of as many pixels, or none) or
// throw InputError.
#include <opencv2/core.hpp>

#include "fuzz_support.h"
#include "ros_message_layout.h"
#include "stocs_ros/common/cloud_conversion.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  stocs::fuzz::ByteReader in(data, size);
  sensor_msgs::PointCloud2 msg;
  msg.width = in.take<uint32_t>();
  msg.height = in.take<uint32_t>();
  msg.point_step = in.take<uint32_t>();
  msg.row_step = in.take<uint32_t>();
  const int fields = in.take<uint8_t>() % 8;
  for (int i = 0; i < fields; ++i) {
    sensor_msgs::PointField f;
    f.name = in.pick(stocs::fuzz::kCloudFieldNames);
    f.offset = in.take<uint32_t>();
    f.datatype = in.take<uint8_t>();
    f.count = in.take<uint32_t>();
    msg.fields.push_back(f);
  }
  msg.data = in.rest();
  stocs::fuzz::tolerateInputError([&] {
    const stocs::OrganizedCloud cloud = stocs_ros::cloudFromMsg(msg);
    if (cloud.points.size() != static_cast<size_t>(msg.width) * msg.height) __builtin_trap();
    const cv::Mat colour = stocs_ros::colourFromCloudMsg(msg);
    if (!colour.empty() && colour.total() != cloud.points.size()) __builtin_trap();
  });
  return 0;
}
