#pragma once
// Pose overlay images: each object's estimated silhouette tinted in its own colour and outlined,
// its ground-truth silhouette outlined in white, over the camera image.

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "stocs/geometry/camera.h"
#include "stocs/geometry/mesh.h"

namespace stocs::tools {

struct OverlayObject {
  const MeshData* model = nullptr;           ///< metres
  std::vector<Eigen::Isometry3f> estimates;  ///< model to camera
  std::vector<Eigen::Isometry3f> truths;     ///< model to camera
  cv::Scalar colour;                         ///< BGR
};

/// Where `model` covers the image at `pose` (CV_8UC1, 255 inside): rasterised for meshes, the
/// projected points closed into a region for point models.
cv::Mat silhouette(const MeshData& model, const Eigen::Isometry3f& pose,
                   const CameraIntrinsics& camera);

/// `background` (CV_8UC3 BGR of the camera's size) with the objects drawn over it.
cv::Mat drawPoseOverlay(const cv::Mat& background, const CameraIntrinsics& camera,
                        const std::vector<OverlayObject>& objects);

/// A distinct, saturated colour for the k-th object.
cv::Scalar objectColour(int k);

}  // namespace stocs::tools
