#pragma once
// Writing the images and JSON files of generated scenes (stocs synth): a view of an arrangement is
// rendered, its depth, colour, masks and probability maps written, and its camera, ground truth,
// visibility and targets recorded for the scene's files. Random views (synthetic_dataset.cpp) and
// sequences (synthetic_sequence.cpp) share it.

#include <chrono>
#include <functional>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "stocs/io/bop_dataset.h"
#include "stocs/io/bop_targets.h"
#include "stocs/sim/bop_writer.h"
#include "stocs/sim/lookalikes.h"
#include "stocs/sim/segmentation_simulator.h"
#include "stocs/sim/synthetic_dataset.h"

namespace stocs {

/// What a scene's JSON files hold, by image id.
struct SceneRecords {
  std::map<int, BopFrameCamera> cameras;
  std::map<int, std::vector<BopGtInstance>> gt;
  std::map<int, std::vector<BopGtInfo>> gt_info;
  std::map<int, std::vector<HandleVisibility>> handles;  ///< images with a handled object
  std::vector<BopTarget> targets;
};

/// One image of a scene to render and write.
struct SceneView {
  int scene = 0, im = 0;
  const std::vector<PlacedObject>* objects = nullptr;  ///< table frame; distractors have id 0
  const std::vector<cv::Vec3b>* colours = nullptr;     ///< BGR, one per object
  Eigen::Isometry3f camera_pose = Eigen::Isometry3f::Identity();  ///< table to camera
  uint64_t image_seed = 0;                                        ///< depth noise and image grain
  uint64_t look_seed = 0;  ///< the light and the backgrounds (scene_look.h)
  /// The objects the image's targets list with their instance counts (0 for one out of view): the
  /// scene's objects in a sequence; null: the objects in the image.
  const std::set<int>* listed = nullptr;
  uint64_t absent_seed = 0;  ///< draws the image's absent objects among the others
  /// The segmentation simulator's seeds of an object's map.
  std::function<SegmentationSeeds(int obj_id)> segmentation_seeds;
};

class SceneWriter {
 public:
  /// `handles`: the handle of each object id that has one (model frame), whose visibility the
  /// scene's scene_handles.json records; `lookalikes`: the models' look-alike pairs, whose absent
  /// member's map marks the present one.
  SceneWriter(const BopDataset& dataset, const SyntheticDatasetParams& params,
              std::vector<std::pair<int, MeshData>> models, std::map<int, MeshData> handles,
              Lookalikes lookalikes,
              const std::function<void(const SyntheticImageReport&)>& progress);

  const std::vector<std::pair<int, MeshData>>& models() const { return models_; }
  const SyntheticDatasetParams& params() const { return params_; }
  const BopDataset& dataset() const { return dataset_; }
  const Lookalikes& lookalikes() const { return lookalikes_; }

  /// Renders the view, writes its images and records its camera, ground truth and targets; then
  /// reports it with the time since `start`.
  void writeView(const SceneView& view, SceneRecords& records,
                 std::chrono::steady_clock::time_point start) const;
  /// scene_camera.json, scene_gt.json and scene_gt_info.json of a scene, and its
  /// scene_handles.json when it has a handled object.
  void writeSceneFiles(int scene, const SceneRecords& records) const;

  /// Up to `absent_per_image` of the dataset's objects that are not in `present`, drawn from a
  /// stream of their own of `seed`, in increasing id order; those with a look-alike in `present`
  /// first.
  std::set<int> absentObjects(const std::set<int>& present, uint64_t seed) const;

 private:
  std::vector<BopTarget> imageTargets(const SceneView& view, const std::set<int>& present,
                                      const std::vector<BopGtInstance>& gt) const;

  const BopDataset& dataset_;
  const SyntheticDatasetParams& params_;
  const std::vector<std::pair<int, MeshData>> models_;
  const std::map<int, MeshData> handles_;
  const Lookalikes lookalikes_;
  const SegmentationNoiseParams segmentation_;
  const DepthNoiseParams noise_;
  const BopFrameCamera camera_;
  const std::function<void(const SyntheticImageReport&)>& progress_;
};

/// Colours (BGR) of placed objects: each dataset object its own; distractors a random colour, or
/// for a share `look.lookalike_share` one within `look.lookalike_jitter` levels of a dataset
/// object's, so that the simulator finds look-alikes and a network cannot go by colour alone.
std::vector<cv::Vec3b> sceneColours(const std::vector<PlacedObject>& objects,
                                    const SceneLookParams& look, Rng& rng);

/// Up to `count` of `ids` that are not in `present`, drawn from a stream of their own of `seed`, in
/// increasing id order: the absent objects of an image's targets. Those with a look-alike in
/// `present` are drawn first (without look-alikes the draws are as they always were).
std::set<int> drawAbsentObjects(const std::vector<int>& ids, const std::set<int>& present,
                                int count, uint64_t seed, const Lookalikes& lookalikes = {});

/// Creates the folder of `file` and writes `image`; throws InputError when it cannot.
void writeImage(const std::filesystem::path& file, const cv::Mat& image);

}  // namespace stocs
