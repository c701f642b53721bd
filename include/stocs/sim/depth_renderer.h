#pragma once
// Z-buffer rasterisation of triangle meshes into a depth image, an instance label image, a
// normal image and, once a mesh with vertex colours is drawn, a colour image, for generated scenes
// and for visible masks of objects at known poses. CPU only: OpenCV images and Eigen maths are
// enough at 640 x 480.

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <vector>

#include "stocs/geometry/camera.h"
#include "stocs/geometry/mesh.h"

namespace stocs {

class DepthRenderer {
 public:
  /// An empty scene seen by `camera`; throws InputError for invalid intrinsics.
  explicit DepthRenderer(const CameraIntrinsics& camera);

  /// Adds `mesh` (metres, triangles wound counter-clockwise seen from outside) at `pose` (mesh to
  /// camera) with `label` (> 0). Nearer surfaces hide farther ones whatever the drawing order.
  /// Triangles with a vertex closer than 1 cm to the camera plane are skipped. A mesh with
  /// colours (one per vertex, else InputError) paints colours() where it is visible.
  void draw(const MeshData& mesh, const Eigen::Isometry3f& pose, int label);

  /// Adds a model without faces (BOP point models): each point covers a square of half-side
  /// `radius` metres at its depth (at least its own pixel), with the normal facing the camera. A
  /// radius near the point spacing closes the surface.
  void drawPoints(const std::vector<Eigen::Vector3f>& points, const Eigen::Isometry3f& pose,
                  float radius, int label);

  /// Depth along the optical axis (CV_32FC1, metres, 0 where nothing was drawn).
  const cv::Mat& depth() const { return depth_; }
  /// Label of the visible surface (CV_32SC1, 0 where nothing was drawn).
  const cv::Mat& labels() const { return labels_; }
  /// Unit normal of the visible surface in the camera frame, facing the camera (CV_32FC3).
  const cv::Mat& normals() const { return normals_; }
  /// Colour of the visible surface (CV_8UC4, RGBA as MeshData::colours), interpolated across its
  /// triangle from the vertices of known colour; alpha 0 where the surface has no known colour.
  /// Empty until a mesh with colours is drawn.
  const cv::Mat& colours() const { return colours_; }
  const CameraIntrinsics& camera() const { return camera_; }

 private:
  CameraIntrinsics camera_;
  cv::Mat depth_, labels_, normals_, colours_;
};

}  // namespace stocs
