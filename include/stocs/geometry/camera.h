#pragma once

#include <Eigen/Core>

namespace stocs {

/// Pinhole intrinsics of an image of width x height pixels.
struct CameraIntrinsics {
  double fx = 0, fy = 0, cx = 0, cy = 0;
  int width = 0, height = 0;

  bool valid() const { return fx > 0 && fy > 0 && width > 0 && height > 0; }

  /// Pixel coordinates (u right, v down) of a point in the camera optical frame (z > 0).
  Eigen::Vector2f project(const Eigen::Vector3f& p) const {
    return {static_cast<float>(fx * p.x() / p.z() + cx),
            static_cast<float>(fy * p.y() / p.z() + cy)};
  }
};

}  // namespace stocs
