#include "geometric_probability_source.h"

#include <fmt/format.h>

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
  bool namesObjects() const override { return false; }  // every region of an object's size

  bool available(int, int, int obj_id) const override { return dataset_.hasModel(obj_id); }

  cv::Mat load(int scene_id, int im_id, int obj_id) const override {
    const ObjectLook& object = look(obj_id);
    return objectProbability(frame(scene_id, im_id), object.size, segmenter_.params(),
                             &object.colours);
  }

 private:
  struct ObjectLook {
    ObjectSize size;
    ChromaticityHistogram colours;
  };

  /// The object's size and colours from its model file (BOP: millimetres), measured once.
  const ObjectLook& look(int obj_id) const {
    auto it = looks_.find(obj_id);
    if (it == looks_.end()) {
      const MeshData mesh = loadMesh(dataset_.modelPath(obj_id).string(), 0.001f);
      it = looks_
               .emplace(obj_id,
                        ObjectLook{ObjectSize::of(mesh.vertices), ChromaticityHistogram::of(mesh)})
               .first;
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
      GeometricSegmentation segmentation =
          segmenter_.segment(depth, camera->second.intrinsics(depth.cols, depth.rows),
                             camera->second.depth_scale / 1000.0);
      const cv::Mat colour = dataset_.loadColour(scene_id, im_id, depth.size());
      if (!colour.empty()) addRegionColours(segmentation, colour);
      cached_.emplace(key, std::move(segmentation));
    }
    return cached_->second;
  }

  const BopDataset& dataset_;
  mutable GeometricSegmenter segmenter_;
  mutable std::map<int, ObjectLook> looks_;
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
