#pragma once
// Depth input messages to the core's organized cloud, and back for the scene publisher:
// sensor_msgs/PointCloud2 (organized, float32 x y z, and a packed rgb field for colour; any other
// fields ignored) and a depth image
// with its camera_info (REP 118: 16UC1 in millimetres, 32FC1 in metres). Errors are
// stocs::InputError naming the field or size at fault.

#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include "stocs/geometry/camera.h"
#include "stocs/geometry/organized_cloud.h"

namespace cv {
class Mat;
}

namespace stocs_ros {

/// The organized cloud (metres, optical frame; NaN or z <= 0 for no measurement). Rejects empty
/// or unorganized (height 1) clouds, missing or non-float32 x/y/z fields and truncated data.
stocs::OrganizedCloud cloudFromMsg(const sensor_msgs::PointCloud2& msg);

/// The cloud's packed `rgb` (or `rgba`) field (PCL's layout) as a CV_8UC3 BGR image the cloud's
/// size; empty without such a field. Call after cloudFromMsg accepted the cloud's layout.
cv::Mat colourFromCloudMsg(const sensor_msgs::PointCloud2& msg);

/// Pinhole intrinsics from K. Rejects a non-positive focal length, an empty image size, and
/// binning or a region of interest (the depth image must be the full, unbinned image).
stocs::CameraIntrinsics intrinsicsFromCameraInfo(const sensor_msgs::CameraInfo& info);

/// Back-projects a REP 118 depth image (16UC1/mono16 mm or 32FC1 m) with its camera_info.
stocs::OrganizedCloud cloudFromDepthImage(const sensor_msgs::ImageConstPtr& depth,
                                          const sensor_msgs::CameraInfo& info);

/// An organized PointCloud2 (x y z float32, plus packed rgb when `bgr` is a CV_8UC3 image of the
/// same size; an empty `bgr` gives XYZ only). Invalid points are NaN.
sensor_msgs::PointCloud2 cloudToMsg(const stocs::OrganizedCloud& cloud, const cv::Mat& bgr);

}  // namespace stocs_ros
