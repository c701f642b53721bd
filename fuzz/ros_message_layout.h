#pragma once
// How the ROS fuzz targets turn bytes into sensor_msgs fields (and how the corpus generator writes
// seeds): little-endian values in a fixed order, the rest of the input is the message's data.
// Filling fields this way, rather than deserialising with ros::serialization, keeps the fuzzer on
// our conversion: ROS's deserialiser resizes arrays to any length prefix before checking the
// buffer, so most inputs would only measure that allocation.
//
// Cloud:  u32 width, height, point_step, row_step; u8 field count (mod 8); per field u8 name
//         (index into kCloudFieldNames), u32 offset, u8 datatype, u32 count; then data.
// Image:  u32 width, height, step; u8 encoding (index into kImageEncodings); u8 channel count for
//         the multi-channel probability conversion; camera info u32 width, height, binning_x,
//         binning_y and f64 fx, fy, cx, cy; then data.

#include "byte_io.h"

namespace stocs::fuzz {

inline const char* const kCloudFieldNames[] = {"x", "y", "z", "rgb", "intensity", ""};
inline const char* const kImageEncodings[] = {
    "mono8", "mono16", "8UC1",  "8UC3", "16UC1", "16UC2", "16SC1",       "32FC1",
    "32FC3", "64FC1",  "32SC1", "8SC1", "bgr8",  "rgba8", "bayer_rggb8", "yuv422",
    "",      "32FC0",  "7UC1",  "8UC5", "16FC1", "64FC4", "bgr16"};

}  // namespace stocs::fuzz
