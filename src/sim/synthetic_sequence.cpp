#include "synthetic_sequence.h"

#include <algorithm>
#include <cmath>

#include "stocs/sim/sequence_info.h"
#include "stocs/sim/sequence_script.h"
#include "stocs/util/random.h"

namespace stocs {
namespace {

/// Streams of the scene's seed, apart from the random views' streams.
enum Stream : uint64_t { kArrangement = 0x5e0, kAbsent, kSegmentation, kImages, kLook };

}  // namespace

std::vector<BopTarget> writeSequenceScene(const SceneWriter& writer, int scene) {
  const SyntheticDatasetParams& params = writer.params();
  const uint64_t scene_seed = streamSeed(params.seed, static_cast<uint64_t>(scene));
  Rng rng(streamSeed(scene_seed, kArrangement));
  std::vector<PlacedObject> objects = arrangeObjects(writer.models(), params.layout, rng);
  std::vector<cv::Vec3b> colours = sceneColours(objects, params.look, rng);
  std::set<int> listed;
  for (const PlacedObject& o : objects) {
    if (o.obj_id > 0) listed.insert(o.obj_id);
  }
  const SequenceScript script(std::move(objects), std::move(colours), params.sequence,
                              params.layout, rng);
  SceneRecords records;
  std::vector<int> im_ids;
  for (int im = 0; im < params.sequence.frames; ++im) {
    const auto start = std::chrono::steady_clock::now();
    const SequenceFrameObjects frame = script.at(im);
    SceneView view;
    view.scene = scene;
    view.im = im;
    view.objects = &frame.objects;
    view.colours = &frame.colours;
    view.camera_pose = script.camera(im);
    view.image_seed = streamSeed(streamSeed(scene_seed, kImages), im);
    view.look_seed = streamSeed(scene_seed, kLook);  // one light and table for the sequence
    view.listed = &listed;
    view.absent_seed = streamSeed(scene_seed, kAbsent);
    view.segmentation_seeds = [&](int obj_id) {
      // Keyframes one second apart.
      return keyframeSeeds(streamSeed(streamSeed(scene_seed, kSegmentation), obj_id), im,
                           std::max(1, static_cast<int>(std::lround(params.sequence.rate_hz))));
    };
    writer.writeView(view, records, start);
    im_ids.push_back(im);
  }
  writer.writeSceneFiles(scene, records);
  SequenceInfo info = evenlyTimed(im_ids, params.sequence.rate_hz);
  info.events = script.events();
  writeSequenceInfo(sequenceInfoPath(writer.dataset().sceneDir(scene)), info);
  return records.targets;
}

}  // namespace stocs
