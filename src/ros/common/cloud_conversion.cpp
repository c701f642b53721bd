#include "stocs_ros/common/cloud_conversion.h"

#include <fmt/format.h>
#include <sensor_msgs/image_encodings.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <opencv2/core.hpp>

#include "stocs/util/error.h"
#include "stocs_ros/common/image_conversion.h"

namespace stocs_ros {
namespace enc = sensor_msgs::image_encodings;
using stocs::InputError;

stocs::OrganizedCloud cloudFromMsg(const sensor_msgs::PointCloud2& msg) {
  if (msg.width == 0 || msg.height == 0) {
    throw InputError(fmt::format("cloud is empty ({}x{})", msg.width, msg.height));
  }
  if (msg.height == 1) {
    throw InputError(fmt::format(
        "cloud is not organized (height 1, width {}); StoCS needs one point per image pixel",
        msg.width));
  }
  uint32_t offsets[3];
  for (int a = 0; a < 3; ++a) {
    const std::string axis(1, "xyz"[a]);
    const auto field =
        std::find_if(msg.fields.begin(), msg.fields.end(),
                     [&](const sensor_msgs::PointField& f) { return f.name == axis; });
    // In 64 bits: a 32-bit offset + 4 wraps for offsets near 2^32 (found by fuzz_ros_cloud).
    if (field == msg.fields.end() || field->datatype != sensor_msgs::PointField::FLOAT32 ||
        uint64_t{field->offset} + sizeof(float) > msg.point_step) {
      throw InputError(fmt::format("cloud has no float32 field '{}' within its point step", axis));
    }
    offsets[a] = field->offset;
  }
  if (msg.row_step < static_cast<size_t>(msg.width) * msg.point_step ||
      msg.data.size() < static_cast<size_t>(msg.row_step) * msg.height) {
    throw InputError(
        fmt::format("cloud {}x{} has row step {} and {} data bytes; too few for {} "
                    "bytes per point",
                    msg.width, msg.height, msg.row_step, msg.data.size(), msg.point_step));
  }
  stocs::OrganizedCloud cloud(static_cast<int>(msg.width), static_cast<int>(msg.height));
  // By offsets rather than PointCloud2ConstIterator, which does not skip padding at row ends.
  for (uint32_t v = 0; v < msg.height; ++v) {
    for (uint32_t u = 0; u < msg.width; ++u) {
      const uint8_t* point = &msg.data[static_cast<size_t>(v) * msg.row_step + u * msg.point_step];
      Eigen::Vector3f& p = cloud.points[static_cast<size_t>(v) * msg.width + u];
      for (int a = 0; a < 3; ++a) std::memcpy(&p[a], point + offsets[a], sizeof(float));
    }
  }
  return cloud;
}

cv::Mat colourFromCloudMsg(const sensor_msgs::PointCloud2& msg) {
  const auto field = std::find_if(
      msg.fields.begin(), msg.fields.end(),
      [](const sensor_msgs::PointField& f) { return f.name == "rgb" || f.name == "rgba"; });
  if (field == msg.fields.end()) return {};
  const bool packed = field->datatype == sensor_msgs::PointField::FLOAT32 ||
                      field->datatype == sensor_msgs::PointField::UINT32;
  if (!packed || uint64_t{field->offset} + 4 > msg.point_step) {
    throw InputError(
        fmt::format("cloud field '{}' is not a packed 4-byte colour within its point "
                    "step",
                    field->name));
  }
  cv::Mat bgr(static_cast<int>(msg.height), static_cast<int>(msg.width), CV_8UC3);
  for (uint32_t v = 0; v < msg.height; ++v) {
    for (uint32_t u = 0; u < msg.width; ++u) {
      // Packed 0x00RRGGBB, little-endian: the bytes are blue, green, red as OpenCV keeps them.
      const uint8_t* point = &msg.data[static_cast<size_t>(v) * msg.row_step + u * msg.point_step];
      std::memcpy(bgr.ptr<uint8_t>(static_cast<int>(v)) + 3 * u, point + field->offset, 3);
    }
  }
  return bgr;
}

stocs::CameraIntrinsics intrinsicsFromCameraInfo(const sensor_msgs::CameraInfo& info) {
  if (info.binning_x > 1 || info.binning_y > 1 || info.roi.width != 0 || info.roi.height != 0) {
    throw InputError(
        "camera_info uses binning or a region of interest; the depth image must be "
        "the full, unbinned image");
  }
  stocs::CameraIntrinsics k;
  k.fx = info.K[0];
  k.cx = info.K[2];
  k.fy = info.K[4];
  k.cy = info.K[5];
  k.width = static_cast<int>(info.width);
  k.height = static_cast<int>(info.height);
  if (!k.valid()) {
    throw InputError(fmt::format("camera_info is invalid: fx {}, fy {}, size {}x{}", k.fx, k.fy,
                                 k.width, k.height));
  }
  return k;
}

stocs::OrganizedCloud cloudFromDepthImage(const sensor_msgs::ImageConstPtr& depth,
                                          const sensor_msgs::CameraInfo& info) {
  // Checked before the pixels: imageView's own error speaks of probability images.
  const std::string& encoding = depth->encoding;
  if (encoding != enc::TYPE_16UC1 && encoding != enc::MONO16 && encoding != enc::TYPE_32FC1) {
    throw InputError(fmt::format(
        "depth image has encoding '{}'; REP 118 depth is 16UC1 (mm) or 32FC1 (m)", encoding));
  }
  const cv::Mat view = imageView(depth);
  const double metres_per_unit = view.type() == CV_16UC1 ? 0.001 : 1.0;
  return stocs::cloudFromDepth(view, intrinsicsFromCameraInfo(info), metres_per_unit);
}

sensor_msgs::PointCloud2 cloudToMsg(const stocs::OrganizedCloud& cloud, const cv::Mat& bgr) {
  const bool colour = !bgr.empty();
  if (colour && (bgr.type() != CV_8UC3 || bgr.cols != cloud.width || bgr.rows != cloud.height)) {
    throw InputError(fmt::format("colour image {}x{} (type {}) does not fit the {}x{} cloud",
                                 bgr.cols, bgr.rows, bgr.type(), cloud.width, cloud.height));
  }
  sensor_msgs::PointCloud2 msg;
  sensor_msgs::PointCloud2Modifier modifier(msg);
  if (colour) {
    modifier.setPointCloud2FieldsByString(2, "xyz", "rgb");
  } else {
    modifier.setPointCloud2FieldsByString(1, "xyz");
  }
  modifier.resize(cloud.points.size());
  msg.width = cloud.width;
  msg.height = cloud.height;
  msg.row_step = msg.width * msg.point_step;
  msg.is_dense = false;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  sensor_msgs::PointCloud2Iterator<float> x(msg, "x");
  for (size_t i = 0; i < cloud.points.size(); ++i, ++x) {
    const bool valid = cloud.isValid(static_cast<int>(i));
    for (int a = 0; a < 3; ++a) x[a] = valid ? cloud.points[i][a] : nan;
  }
  if (colour) {
    sensor_msgs::PointCloud2Iterator<uint8_t> rgb(msg, "rgb");  // packed as b, g, r, unused
    for (int v = 0; v < cloud.height; ++v) {
      for (int u = 0; u < cloud.width; ++u, ++rgb) {
        const cv::Vec3b& p = bgr.at<cv::Vec3b>(v, u);
        rgb[0] = p[0];
        rgb[1] = p[1];
        rgb[2] = p[2];
      }
    }
  }
  return msg;
}

}  // namespace stocs_ros
