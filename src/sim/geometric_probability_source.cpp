#include "geometric_probability_source.h"

#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <opencv2/core.hpp>
#include <optional>

#include "stocs/io/mesh_io.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

class GeometricProbabilitySource : public ProbabilitySource {
 public:
  GeometricProbabilitySource(const BopDataset& dataset, const GeometricSegmentationParams& params)
      : dataset_(dataset), segmenter_(params) {}

  std::string spec() const override { return "geometric"; }

  bool available(int, int, int obj_id) const override {
    std::error_code ec;
    return std::filesystem::exists(dataset_.modelPath(obj_id), ec);
  }

  cv::Mat load(int scene_id, int im_id, int obj_id) const override {
    return objectProbability(frame(scene_id, im_id), size(obj_id), segmenter_.params());
  }

 private:
  /// The object's size from its model file (BOP: millimetres), measured once.
  const ObjectSize& size(int obj_id) const {
    auto it = sizes_.find(obj_id);
    if (it == sizes_.end()) {
      const MeshData mesh = loadMesh(dataset_.modelPath(obj_id).string(), 0.001f);
      it = sizes_.emplace(obj_id, ObjectSize::of(mesh.vertices)).first;
    }
    return it->second;
  }

  /// The frame's segmentation, kept for the objects that follow (one frame at a time).
  const GeometricSegmentation& frame(int scene_id, int im_id) const {
    const auto key = std::make_pair(scene_id, im_id);
    if (!cached_ || cached_->first != key) {
      if (scene_id != camera_scene_) {
        cameras_ = dataset_.sceneCameras(scene_id);
        camera_scene_ = scene_id;
      }
      const auto camera = cameras_.find(im_id);
      if (camera == cameras_.end()) {
        throw InputError(fmt::format("{}: no entry for image {}",
                                     (dataset_.sceneDir(scene_id) / "scene_camera.json").string(),
                                     im_id));
      }
      const cv::Mat depth = dataset_.loadDepth(scene_id, im_id);
      cached_.emplace(key,
                      segmenter_.segment(depth, camera->second.intrinsics(depth.cols, depth.rows),
                                         camera->second.depth_scale / 1000.0));
    }
    return cached_->second;
  }

  const BopDataset& dataset_;
  mutable GeometricSegmenter segmenter_;
  mutable std::map<int, ObjectSize> sizes_;
  mutable int camera_scene_ = -1;
  mutable std::map<int, BopFrameCamera> cameras_;
  mutable std::optional<std::pair<std::pair<int, int>, GeometricSegmentation>> cached_;
};

}  // namespace

std::unique_ptr<ProbabilitySource> makeGeometricProbabilitySource(
    const BopDataset& dataset, const GeometricSegmentationParams& params) {
  return std::make_unique<GeometricProbabilitySource>(dataset, params);
}

}  // namespace stocs
