#pragma once
// The sidecar of a sequence scene, `test/{scene:06d}/scene_events.json` (BOP has no timestamps):
// the frame rate, each image's time and the object events with their frame ranges, so that a
// player keeps the rate, a tracker gets the times and a benchmark marks the events. `stocs synth
// --sequence` and `stocs simmaps` write it; the scene publisher reads it.
//
//   {"rate_hz": 30.0,
//    "stamps": {"0": 0.0, "1": 0.033333, ...},           // seconds from the first frame, by im_id
//    "events": [{"kind": "push", "obj_id": 3, "first_frame": 30, "last_frame": 74}, ...]}

#include <filesystem>
#include <map>
#include <optional>
#include <vector>

#include "stocs/io/bop_dataset.h"
#include "stocs/sim/sequence_script.h"

namespace stocs {

struct SequenceInfo {
  double rate_hz = 30;
  std::map<int, double> stamps;  ///< seconds from the first frame, by image id
  std::vector<SequenceEvent> events;
};

/// scene_events.json of scene folder `scene_dir`.
std::filesystem::path sequenceInfoPath(const std::filesystem::path& scene_dir);

/// The times of images `im_ids` taken one after another at `rate_hz`, the first at 0.
SequenceInfo evenlyTimed(const std::vector<int>& im_ids, double rate_hz);

void writeSequenceInfo(const std::filesystem::path& file, const SequenceInfo& info);

/// Throws InputError naming the file and the problem: unreadable, not JSON, a rate that is not
/// positive, times that do not increase with the image id, an unknown event kind or an event whose
/// frames are reversed.
SequenceInfo readSequenceInfo(const std::filesystem::path& file);

/// The frame rate of the sequences among `scenes` of `dataset` (those with a scene_events.json);
/// none when no scene has one. Throws InputError when two rates differ, naming both scenes, or when
/// a file is bad.
std::optional<double> sequenceRate(const BopDataset& dataset, const std::vector<int>& scenes);

}  // namespace stocs
