#pragma once
// A real BOP dataset without network maps made playable as a sequence (`stocs simmaps`): a new
// dataset folder that links to the source's models and images and adds the segmentation
// simulator's maps in `prob/`, BOP's targets file and each scene's scene_events.json (frame times
// at a given rate, images in id order), e.g. for the five consecutive YCB-Video frames of
// ycbv-0000. The source is only read.

#include <cstdint>
#include <filesystem>
#include <string>

namespace stocs {

struct SimulatedMapsParams {
  std::string segmentation_preset = "mild";
  int absent_per_image = 2;  ///< objects of models/ not in a scene, with inst_count 0 and a map
  double rate_hz = 30;       ///< frame rate of the sequence the images form
  uint64_t seed = 0;
};

/// Writes the dataset to `out`, which must not exist or be empty: `models/` and each scene's image
/// folders (rgb/, depth/, mask_visib/, edge/) as symbolic links to the source's, its JSON files
/// copied, `prob/{im}_{obj}.png` for every target (the objects of scene_gt.json, and per scene
/// `absent_per_image` others; maps of one object drift smoothly from frame to frame as in
/// generated sequences), `test_targets_bop19.json` and scene_events.json. Throws InputError
/// naming the problem.
void writeSimulatedMapsDataset(const std::filesystem::path& source,
                               const std::filesystem::path& out, const SimulatedMapsParams& params);

}  // namespace stocs
