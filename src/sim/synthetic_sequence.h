#pragma once
// Writing a generated sequence (`stocs synth --sequence`): one scene's frames rendered in order
// from its SequenceScript, and its scene_events.json.

#include <vector>

#include "scene_writer.h"

namespace stocs {

/// Writes scene `scene` as a sequence: an arrangement from the scene's random stream, the script's
/// frames as images 0..frames-1, the scene's JSON files and scene_events.json; returns the targets.
/// Every frame's targets list every object of the arrangement (inst_count 0 while one is removed)
/// and the same absent objects. An object's segmentation errors change smoothly: its map blends
/// the random layouts of keyframes one second apart.
std::vector<BopTarget> writeSequenceScene(const SceneWriter& writer, int scene);

}  // namespace stocs
