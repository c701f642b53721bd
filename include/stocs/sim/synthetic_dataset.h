#pragma once
// Generated BOP datasets (`stocs synth`): cluttered tabletop scenes of the project's objects (or
// of any BOP models folder) with distractors, sensor-like depth, a shaded RGB image, visible masks,
// visibility statistics and the segmentation simulator's probability maps in `prob/`, in the same
// layout as the real datasets, so every tool runs on them unchanged. `test_targets_bop19.json`
// lists every (image, object) to estimate: the objects of scene_gt.json and absent ones (inst_count
// 0). With `sequence.enabled` each scene is a sequence: consecutive frames of a moving camera
// with object events, described in the scene's scene_events.json (sequence_info.h).

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "stocs/geometry/camera.h"
#include "stocs/sim/depth_noise.h"
#include "stocs/sim/scene_layout.h"
#include "stocs/sim/scene_look.h"
#include "stocs/sim/sequence_script.h"
#include "stocs/sim/synthetic_frame.h"

namespace stocs {

struct SyntheticDatasetParams {
  int scenes = 1;            ///< arrangements, test/{scene:06d}
  int images_per_scene = 1;  ///< views of each arrangement
  SceneLayoutParams layout;
  CameraIntrinsics camera = defaultSynthCamera();
  DepthNoiseParams depth_noise;  ///< the sensor model at level 1
  float depth_noise_level = 1;   ///< 0: exact depth
  std::string segmentation_preset = "mild";
  /// Objects per image that are not in the scene but get a probability map and a target with
  /// inst_count 0 (fewer when the models run out): the right answer for them is no pose.
  int absent_per_image = 2;
  double depth_scale = 0.1;  ///< mm per depth unit: 0.1 reaches 6.5 m
  uint64_t seed = 0;
  /// With `sequence.enabled`, each scene is a sequence of `sequence.frames` consecutive frames
  /// (sequence_script.h) instead of `images_per_scene` random views.
  SequenceParams sequence;
  /// Variation of the colour images: light, table and background, look-alike distractors.
  SceneLookParams look;
  /// The generated objects without a models folder (catalogueSelectionNames()): "standard", or
  /// "textured" / "all" for the vertex-coloured objects of texturedCatalogue().
  std::string catalogue = "standard";
  /// With `bin.object`, each scene is a packed bin of that object instead of a tabletop.
  PackedBinParams bin;

  /// Key, range, unit and meaning of every field but the camera and the depth noise model (the
  /// options of `stocs synth`).
  static const ParamSet<SyntheticDatasetParams>& schema();
  /// Throws InputError naming the first value out of range (and an unknown preset).
  void validate() const;
};

/// What was generated in one image.
struct SyntheticImageReport {
  int scene_id = 0, im_id = 0;
  int objects = 0;     ///< ground-truth instances
  double seconds = 0;  ///< generating and writing the image
};

/// Writes the dataset to `root`, which must not exist or be empty. Models come from `models_dir`
/// (its obj_*.ply, models_info.json and lookalikes.json are copied) or, when it is empty, from the
/// catalogue selection `params.catalogue` (its look-alike pairs written to models/lookalikes.json
/// when it declares any). A scene with a handled object (a mug) gets scene_handles.json:
/// how much of each such instance's handle each image shows.
/// `progress` is called after each image. Deterministic for a seed: the same files every time.
/// Throws InputError naming the problem.
void writeSyntheticDataset(const std::filesystem::path& root, const SyntheticDatasetParams& params,
                           const std::filesystem::path& models_dir = {},
                           const std::function<void(const SyntheticImageReport&)>& progress = {});

}  // namespace stocs
