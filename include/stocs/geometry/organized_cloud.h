#pragma once
// An organized point cloud: one 3D point per pixel in the camera optical frame, metres, NaN where
// the sensor measured nothing. Everything the core does on a scene starts from this.

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "stocs/geometry/camera.h"

namespace cv {
class Mat;
}

namespace stocs {

struct OrganizedCloud {
  int width = 0;
  int height = 0;
  std::vector<Eigen::Vector3f> points;  // row-major, size width * height

  OrganizedCloud() = default;
  OrganizedCloud(int w, int h);

  bool isValid(int index) const {
    return std::isfinite(points[index].z()) && points[index].z() > 0;
  }
  const Eigen::Vector3f& at(int u, int v) const { return points[v * width + u]; }
  int validCount() const;
};

/// Back-projects a depth image (CV_16UC1 or CV_32FC1, `metres_per_unit` per value; 0, NaN and
/// negative values mean "no measurement"). Throws InputError on a wrong type or a size that does
/// not match the intrinsics.
OrganizedCloud cloudFromDepth(const cv::Mat& depth, const CameraIntrinsics& camera,
                              double metres_per_unit);

/// Recovers pinhole intrinsics from an organized cloud by least squares on u = fx x/z + cx and
/// v = fy y/z + cy over its valid points, for clouds that come without camera_info. Throws
/// InputError when fewer than 3 rows and columns hold valid points.
CameraIntrinsics intrinsicsFromCloud(const OrganizedCloud& cloud);

}  // namespace stocs
