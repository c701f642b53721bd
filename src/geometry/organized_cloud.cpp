#include "stocs/geometry/organized_cloud.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <limits>
#include <opencv2/core.hpp>

#include "stocs/util/error.h"

namespace stocs {

OrganizedCloud::OrganizedCloud(int w, int h)
    : width(w),
      height(h),
      points(static_cast<size_t>(w) * h,
             Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN())) {}

int OrganizedCloud::validCount() const {
  int n = 0;
  for (size_t i = 0; i < points.size(); ++i) n += isValid(static_cast<int>(i));
  return n;
}

OrganizedCloud cloudFromDepth(const cv::Mat& depth, const CameraIntrinsics& camera,
                              double metres_per_unit) {
  if (!camera.valid())
    throw InputError("camera intrinsics are invalid (fx, fy, width, height > 0)");
  if (depth.empty()) throw InputError("depth image is empty");
  if (depth.channels() != 1 || (depth.depth() != CV_16U && depth.depth() != CV_32F)) {
    throw InputError(fmt::format(
        "depth image has {} channel(s) of OpenCV depth {}; expected one channel of 16UC1 or 32FC1",
        depth.channels(), depth.depth()));
  }
  if (depth.cols != camera.width || depth.rows != camera.height) {
    throw InputError(fmt::format("depth image is {}x{} but the camera is {}x{}", depth.cols,
                                 depth.rows, camera.width, camera.height));
  }
  if (!(metres_per_unit > 0) || !std::isfinite(metres_per_unit)) {
    throw InputError(fmt::format("depth scale {} is not a positive number", metres_per_unit));
  }
  OrganizedCloud cloud(depth.cols, depth.rows);
  for (int v = 0; v < depth.rows; ++v) {
    for (int u = 0; u < depth.cols; ++u) {
      const double raw = depth.depth() == CV_16U ? depth.at<uint16_t>(v, u) : depth.at<float>(v, u);
      if (!(raw > 0) || !std::isfinite(raw)) continue;
      const double z = raw * metres_per_unit;
      cloud.points[v * depth.cols + u] = Eigen::Vector3f(
          static_cast<float>((u - camera.cx) * z / camera.fx),
          static_cast<float>((v - camera.cy) * z / camera.fy), static_cast<float>(z));
    }
  }
  return cloud;
}

CameraIntrinsics intrinsicsFromCloud(const OrganizedCloud& cloud) {
  // Two independent 1D fits: u against x/z and v against y/z, each [slope, offset].
  Eigen::Matrix2d au = Eigen::Matrix2d::Zero(), av = Eigen::Matrix2d::Zero();
  Eigen::Vector2d bu = Eigen::Vector2d::Zero(), bv = Eigen::Vector2d::Zero();
  // About 60 samples per image axis are plenty for four unknowns and keep this cheap.
  const int stride = std::max(1, std::min(cloud.width, cloud.height) / 60);
  int used = 0;
  for (int v = 0; v < cloud.height; v += stride) {
    for (int u = 0; u < cloud.width; u += stride) {
      const int i = v * cloud.width + u;
      if (!cloud.isValid(i)) continue;
      const Eigen::Vector3f& p = cloud.points[i];
      const double xn = p.x() / p.z(), yn = p.y() / p.z();
      au += Eigen::Vector2d(xn, 1) * Eigen::RowVector2d(xn, 1);
      bu += Eigen::Vector2d(xn, 1) * u;
      av += Eigen::Vector2d(yn, 1) * Eigen::RowVector2d(yn, 1);
      bv += Eigen::Vector2d(yn, 1) * v;
      ++used;
    }
  }
  if (used < 9 || std::abs(au.determinant()) < 1e-12 || std::abs(av.determinant()) < 1e-12) {
    throw InputError(fmt::format(
        "organized cloud {}x{} has too few valid points ({}) spread over rows and columns to "
        "recover its camera intrinsics",
        cloud.width, cloud.height, used));
  }
  const Eigen::Vector2d su = au.ldlt().solve(bu), sv = av.ldlt().solve(bv);
  CameraIntrinsics k;
  k.fx = su[0];
  k.cx = su[1];
  k.fy = sv[0];
  k.cy = sv[1];
  k.width = cloud.width;
  k.height = cloud.height;
  if (!k.valid()) throw InputError("organized cloud does not look like a pinhole camera image");
  return k;
}

}  // namespace stocs
