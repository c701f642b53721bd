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

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace stocs::fuzz {

inline const char* const kCloudFieldNames[] = {"x", "y", "z", "rgb", "intensity", ""};
inline const char* const kImageEncodings[] = {
    "mono8", "mono16", "8UC1",  "8UC3", "16UC1", "16UC2", "16SC1",       "32FC1",
    "32FC3", "64FC1",  "32SC1", "8SC1", "bgr8",  "rgba8", "bayer_rggb8", "yuv422",
    "",      "32FC0",  "7UC1",  "8UC5", "16FC1", "64FC4", "bgr16"};

/// Reads values front to back; past the end every value is zero.
class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  template <class T>
  T take() {
    T v{};
    if (size_ - pos_ >= sizeof(T)) {
      std::memcpy(&v, data_ + pos_, sizeof(T));
      pos_ += sizeof(T);
    } else {
      pos_ = size_;
    }
    return v;
  }
  template <size_t N>
  const char* pick(const char* const (&names)[N]) {
    return names[take<uint8_t>() % N];
  }
  std::vector<uint8_t> rest() { return {data_ + pos_, data_ + size_}; }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
};

/// The generator's side of ByteReader.
class ByteWriter {
 public:
  template <class T>
  ByteWriter& put(T v) {
    const auto* p = reinterpret_cast<const char*>(&v);
    bytes_.append(p, sizeof(T));
    return *this;
  }
  ByteWriter& append(const std::string& raw) {
    bytes_ += raw;
    return *this;
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

}  // namespace stocs::fuzz
