#include "stocs/sim/simulated_maps.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <set>

#include "scene_writer.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/io/bop_targets.h"
#include "stocs/sim/ground_truth_masks.h"
#include "stocs/sim/segmentation_simulator.h"
#include "stocs/sim/sequence_info.h"
#include "stocs/util/error.h"
#include "stocs/util/random.h"

namespace stocs {
namespace fs = std::filesystem;

namespace {

/// Links `to` at `link` when it exists.
void linkIfPresent(const fs::path& to, const fs::path& link) {
  std::error_code ec;
  if (!fs::exists(to, ec)) return;
  fs::create_directory_symlink(fs::weakly_canonical(fs::absolute(to)), link, ec);
  if (ec) {
    throw InputError(
        fmt::format("simmaps: cannot link {} to {}: {}", link.string(), to.string(), ec.message()));
  }
}

/// Each scene's image folders linked and its JSON files copied.
void linkScenes(const BopDataset& source, const BopDataset& out) {
  for (int scene : source.sceneIds()) {
    const fs::path from = source.sceneDir(scene), to = out.sceneDir(scene);
    fs::create_directories(to);
    for (const char* folder : {"rgb", "depth", "mask_visib", "edge"}) {
      linkIfPresent(from / folder, to / folder);
    }
    for (const char* file : {"scene_camera.json", "scene_gt.json", "scene_gt_info.json"}) {
      if (!fs::exists(from / file)) continue;
      fs::copy_file(from / file, to / file);
      // A read-only source file makes a read-only copy; the copy is the user's to change.
      fs::permissions(to / file, fs::perms::owner_write, fs::perm_options::add);
    }
  }
}

/// Writes the maps of every target of one scene and returns the targets.
std::vector<BopTarget> writeSceneMaps(const BopDataset& source, const BopDataset& out, int scene,
                                      const SimulatedMapsParams& params) {
  const GroundTruthMasks masks(source);
  const SegmentationNoiseParams preset = segmentationPreset(params.segmentation_preset);
  const std::map<int, std::vector<BopGtInstance>> gt = source.sceneGroundTruth(scene);
  std::vector<int> ids;
  std::set<int> listed;
  for (const auto& [id, info] : source.modelsInfo()) ids.push_back(id);
  for (const auto& [im, instances] : gt) {
    for (const BopGtInstance& g : instances) listed.insert(g.obj_id);
  }
  const uint64_t scene_seed = streamSeed(params.seed, static_cast<uint64_t>(scene));
  std::set<int> targets_objects = listed;
  for (int id : drawAbsentObjects(ids, listed, params.absent_per_image, scene_seed)) {
    targets_objects.insert(id);
  }
  const int period = std::max(1, static_cast<int>(std::lround(params.rate_hz)));
  std::vector<BopTarget> targets;
  int frame = 0;
  for (const auto& [im, instances] : gt) {
    const SegmentationScene seen = masks.frame(scene, im);
    for (int obj : targets_objects) {
      const auto count = std::count_if(instances.begin(), instances.end(),
                                       [obj](const BopGtInstance& g) { return g.obj_id == obj; });
      targets.push_back({scene, im, obj, static_cast<int>(count)});
      const cv::Mat probability = simulateSegmentation(
          seen, obj, preset, keyframeSeeds(streamSeed(scene_seed, obj), frame, period));
      cv::Mat prob16;
      probability.convertTo(prob16, CV_16UC1, 10000.0);
      writeImage(out.probabilityPath(scene, im, obj), prob16);
    }
    ++frame;
  }
  std::vector<int> im_ids;
  for (const auto& [im, instances] : gt) im_ids.push_back(im);
  writeSequenceInfo(sequenceInfoPath(out.sceneDir(scene)), evenlyTimed(im_ids, params.rate_hz));
  return targets;
}

}  // namespace

void writeSimulatedMapsDataset(const fs::path& source_root, const fs::path& out,
                               const SimulatedMapsParams& params) {
  segmentationPreset(params.segmentation_preset);
  if (params.absent_per_image < 0) {
    throw InputError(fmt::format("simmaps: --absent {} is negative", params.absent_per_image));
  }
  if (!(params.rate_hz > 0 && params.rate_hz <= 1000)) {
    throw InputError(fmt::format("simmaps: --rate {} Hz is outside (0, 1000]", params.rate_hz));
  }
  const BopDataset source(source_root);
  std::error_code ec;
  if (fs::exists(out, ec) && !fs::is_empty(out, ec)) {
    throw InputError(fmt::format("simmaps: {} exists and is not empty", out.string()));
  }
  fs::create_directories(out / "test");
  linkIfPresent(source.root() / "models", out / "models");
  const BopDataset written(out);
  linkScenes(source, written);
  std::vector<BopTarget> targets;
  for (int scene : source.sceneIds()) {
    const std::vector<BopTarget> scene_targets = writeSceneMaps(source, written, scene, params);
    targets.insert(targets.end(), scene_targets.begin(), scene_targets.end());
  }
  writeBopTargets(out / "test_targets_bop19.json", targets);
}

}  // namespace stocs
