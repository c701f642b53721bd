#include "stocs/sim/ground_truth_masks.h"

#include <fmt/format.h>

#include <opencv2/imgcodecs.hpp>

#include "stocs/geometry/normals.h"
#include "stocs/io/mesh_io.h"
#include "stocs/sim/depth_renderer.h"
#include "stocs/sim/lookalikes.h"
#include "stocs/util/error.h"

namespace stocs {

GroundTruthMasks::GroundTruthMasks(const BopDataset& dataset)
    : dataset_(dataset), lookalikes_(readLookalikes(lookalikesPath(dataset.root()))) {}

const MeshData& GroundTruthMasks::model(int obj_id) const {
  auto it = models_.find(obj_id);
  if (it == models_.end()) {
    it = models_.emplace(obj_id, loadMesh(dataset_.modelPath(obj_id).string(), 0.001f)).first;
    // Point models are splatted over 1.5 median nearest-neighbour distances: irregular samples
    // leave gaps wider than that distance, and the silhouette grows by about a millimetre only.
    if (!it->second.isMesh()) splat_radius_[obj_id] = 1.5f * medianSpacing(it->second.vertices);
  }
  return it->second;
}

bool GroundTruthMasks::hasMaskVisib(int scene_id, int im_id, size_t instances) const {
  std::error_code ec;
  for (size_t i = 0; i < instances; ++i) {
    if (!std::filesystem::exists(dataset_.maskVisibPath(scene_id, im_id, static_cast<int>(i)), ec))
      return false;
  }
  return instances > 0;
}

SegmentationScene GroundTruthMasks::frame(int scene_id, int im_id) const {
  const std::map<int, std::vector<BopGtInstance>> gt = dataset_.sceneGroundTruth(scene_id);
  const auto instances = gt.find(im_id);
  if (instances == gt.end()) {
    throw InputError(fmt::format("{}: no entry for image {}",
                                 (dataset_.sceneDir(scene_id) / "scene_gt.json").string(), im_id));
  }
  SegmentationScene scene;
  scene.lookalikes = lookalikes_;
  for (const BopGtInstance& g : instances->second) scene.obj_ids.push_back(g.obj_id);
  const cv::Mat depth = dataset_.loadDepth(scene_id, im_id);
  std::error_code ec;
  if (std::filesystem::exists(dataset_.rgbPath(scene_id, im_id), ec)) {
    scene.rgb = cv::imread(dataset_.rgbPath(scene_id, im_id).string(), cv::IMREAD_COLOR);
    if (scene.rgb.size() != depth.size()) {
      throw InputError(fmt::format("{}: RGB image is {}x{} but the depth image is {}x{}",
                                   dataset_.rgbPath(scene_id, im_id).string(), scene.rgb.cols,
                                   scene.rgb.rows, depth.cols, depth.rows));
    }
  }

  if (hasMaskVisib(scene_id, im_id, scene.obj_ids.size())) {
    scene.labels = cv::Mat(depth.size(), CV_32SC1, cv::Scalar(0));
    for (size_t i = 0; i < scene.obj_ids.size(); ++i) {
      const std::filesystem::path file =
          dataset_.maskVisibPath(scene_id, im_id, static_cast<int>(i));
      const cv::Mat mask = cv::imread(file.string(), cv::IMREAD_GRAYSCALE);
      if (mask.size() != depth.size()) {
        throw InputError(fmt::format("{}: mask is {}x{} but the depth image is {}x{}",
                                     file.string(), mask.cols, mask.rows, depth.cols, depth.rows));
      }
      scene.labels.setTo(static_cast<int>(i) + 1, mask > 0);
    }
    return scene;
  }

  const std::map<int, BopFrameCamera> cameras = dataset_.sceneCameras(scene_id);
  const auto camera = cameras.find(im_id);
  if (camera == cameras.end()) {
    throw InputError(fmt::format("{}: no entry for image {}",
                                 (dataset_.sceneDir(scene_id) / "scene_camera.json").string(),
                                 im_id));
  }
  DepthRenderer renderer(camera->second.intrinsics(depth.cols, depth.rows));
  for (size_t i = 0; i < instances->second.size(); ++i) {
    const BopGtInstance& g = instances->second[i];
    Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
    pose.linear() = g.R.cast<float>();
    pose.translation() = (g.t_mm / 1000.0).cast<float>();
    const MeshData& mesh = model(g.obj_id);
    const int label = static_cast<int>(i) + 1;
    if (mesh.isMesh()) {
      renderer.draw(mesh, pose, label);
    } else {
      renderer.drawPoints(mesh.vertices, pose, splat_radius_.at(g.obj_id), label);
    }
  }
  scene.labels = renderer.labels().clone();
  return scene;
}

}  // namespace stocs
