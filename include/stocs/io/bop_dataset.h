#pragma once
// Reading datasets in the BOP layout (https://bop.felk.cvut.cz), with this project's extension
// `prob/{im:06d}_{obj:06d}.png`: per-pixel class probabilities, uint16, value / 10000.
// Units follow BOP: millimetres for translations and models, depth * depth_scale = mm.

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "stocs/geometry/camera.h"
#include "stocs/model/object_symmetries.h"

#include <opencv2/core/types.hpp>

namespace cv {
class Mat;
}

namespace stocs {

struct BopFrameCamera {
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  double depth_scale = 1.0;  ///< mm per depth unit

  /// Intrinsics for an image of the given size.
  CameraIntrinsics intrinsics(int width, int height) const;
};

struct BopGtInstance {
  int obj_id = 0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  ///< model to camera
  Eigen::Vector3d t_mm = Eigen::Vector3d::Zero();
};

struct ContinuousSymmetry {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d offset_mm = Eigen::Vector3d::Zero();
};

struct BopObjectInfo {
  double diameter_mm = 0;
  std::vector<Eigen::Matrix4d> symmetries_discrete;  ///< translation in mm; identity not listed
  std::vector<ContinuousSymmetry> symmetries_continuous;

  bool symmetric() const { return !symmetries_discrete.empty() || !symmetries_continuous.empty(); }
  /// The symmetries in metres, as estimation takes them (PreparedModel::symmetries).
  ObjectSymmetries symmetries() const;
};

/// A BOP models_info.json, by object id; empty when the file does not exist. Throws InputError
/// naming the file and the problem.
std::map<int, BopObjectInfo> readModelsInfo(const std::filesystem::path& file);

class BopDataset {
 public:
  /// Throws InputError when `root` is not a folder with `models/` and `<split>/`.
  explicit BopDataset(std::filesystem::path root, std::string split = "test");

  const std::filesystem::path& root() const { return root_; }
  std::vector<int> sceneIds() const;
  std::filesystem::path sceneDir(int scene_id) const;

  /// Parsed scene_camera.json / scene_gt.json of a scene, keyed by image id. Throw InputError
  /// naming the file and the problem.
  std::map<int, BopFrameCamera> sceneCameras(int scene_id) const;
  std::map<int, std::vector<BopGtInstance>> sceneGroundTruth(int scene_id) const;
  /// models/models_info.json; empty when the file does not exist.
  std::map<int, BopObjectInfo> modelsInfo() const;

  std::filesystem::path modelPath(int obj_id) const;
  /// Whether the object's model file exists (false, not a throw, where it cannot be checked).
  bool hasModel(int obj_id) const;
  std::filesystem::path depthPath(int scene_id, int im_id) const;
  std::filesystem::path rgbPath(int scene_id, int im_id) const;
  /// The frame's colour image `rgb/{im:06d}.png`, else `.jpg`; empty when it has neither.
  std::filesystem::path colourPath(int scene_id, int im_id) const;
  std::filesystem::path probabilityPath(int scene_id, int im_id, int obj_id) const;
  std::filesystem::path maskVisibPath(int scene_id, int im_id, int gt_index) const;
  /// Extension `edge/{im:06d}.png`: 8-bit instance boundary map, 255 interior, 0 boundary.
  std::filesystem::path boundaryPath(int scene_id, int im_id) const;

  /// 16-bit depth image; throws InputError naming the file when missing or not single-channel 16U.
  cv::Mat loadDepth(int scene_id, int im_id) const;
  /// Probability map as CV_32FC1 in [0, 1] (see toProbabilityImage); throws InputError naming the
  /// file when it is missing or invalid.
  cv::Mat loadProbability(int scene_id, int im_id, int obj_id) const;
  /// Boundary map (CV_8UC1), or an empty image when the frame has none; throws InputError naming
  /// the file when it exists but is not a single-channel 8-bit image.
  cv::Mat loadBoundary(int scene_id, int im_id) const;
  /// Colour image (CV_8UC3 BGR, colourPath), or an empty image when the frame has none; throws
  /// InputError naming the file when it is unreadable or not of `size` (the depth image's).
  cv::Mat loadColour(int scene_id, int im_id, cv::Size size) const;

 private:
  std::filesystem::path root_;
  std::string split_;
};

/// Whole content of a file; throws InputError naming the file when it cannot be opened.
std::string readTextFile(const std::filesystem::path& path);

}  // namespace stocs
