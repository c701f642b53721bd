#pragma once
// Probability maps that behave like a segmentation CNN trained on synthetic data (issue 3), made
// from a frame's visible instance masks: missed regions, bleeding over object outlines, confident
// false positives on neighbouring objects and on pixels that look like the target, and smooth
// low-level noise. The paper's network lost recall from 95.3% on synthetic to 77.9% on real images;
// named presets span that range (their measured precision and recall are in docs/simulator.md).

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "stocs/util/param_set.h"

namespace stocs {

struct SegmentationNoiseParams {
  float confidence = 1.0f;       ///< probability on an object pixel that is found
  float missed_fraction = 0;     ///< mean share of the object's visible pixels that are missed
  float missed_level = 0.1f;     ///< probability left in a missed region
  float bleed_px = 0;            ///< spread of the map over the object's outline, pixels
  float neighbour_fraction = 0;  ///< mean share of each nearby other object that fires
  float lookalike_fraction = 0;  ///< share of the image where look-alike pixels may fire
  /// Colour distance (RGB, 0..255) at which a pixel stops looking like the target: with an RGB
  /// image look-alike firing is scaled by colour similarity, without one it falls on the
  /// background.
  float colour_tolerance = 40;
  float false_positive_level = 0.8f;  ///< probability of a false-positive region
  float blob_px = 14;                 ///< size of missed and false-positive regions, pixels
  float noise = 0;                    ///< amplitude of the smooth low-level noise

  // Maps of absent objects (a target whose object is not among the scene's instances).
  /// Share of absent targets whose map is a confusion with a visible object; the others get
  /// background noise with a few blobs.
  float absent_confusion_share = 0.5f;
  /// Mean probability on the confused object's region relative to `confidence` (drawn per target
  /// in 0.75..1.25 times this): a similar class fires there, below what the right class gets.
  float confusion_level = 0.55f;
  /// The same for the map of an absent object on its visible look-alikes (SegmentationScene::
  /// lookalikes): a network that confuses two objects of one shape marks the present one almost
  /// as it marks it for its own class.
  float lookalike_confusion_level = 0.8f;
  int absent_blobs = 3;            ///< most blobs of a noise map (1 to this many per target)
  float absent_blob_level = 0.4f;  ///< mean peak probability of a blob (0.6..1.4 times per blob)

  /// Key, range, unit and meaning of every field.
  static const ParamSet<SegmentationNoiseParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
};

/// Preset names from clean to very noisy.
std::vector<std::string> segmentationPresetNames();

/// A named preset; throws InputError for an unknown name, listing the known ones.
SegmentationNoiseParams segmentationPreset(const std::string& name);

/// What the simulator sees of a frame.
struct SegmentationScene {
  cv::Mat labels;            ///< CV_32SC1: 1 + index of the instance visible at a pixel, 0 for none
  std::vector<int> obj_ids;  ///< object id of each instance
  cv::Mat rgb;               ///< optional CV_8UC3 colour image of the same size
  /// Look-alikes of each object id (lookalikes.h): an absent target's map marks every visible
  /// instance of its look-alikes.
  std::map<int, std::set<int>> lookalikes = {};
};

/// The simulated probability (CV_32FC1 in [0, 1]) of object `target_obj_id` at every pixel: the
/// same for the same seed. For an object that is not among the scene's instances (an absent
/// target), the map a network could emit for it: where instances of its look-alikes are visible,
/// their regions at `lookalike_confusion_level`; else with probability `absent_confusion_share`
/// another visible instance's region at a confusion level (class confusion), else the low-level
/// noise with a few blobs of moderate probability; kind and strength drawn from the seed. Throws
/// InputError for a label image that is not CV_32SC1, labels without an object id, or an RGB image
/// of another size or type.
cv::Mat simulateSegmentation(const SegmentationScene& scene, int target_obj_id,
                             const SegmentationNoiseParams& params, uint64_t seed);

/// The seeds of a map that changes smoothly from frame to frame: the random layout (missed and
/// false-positive regions, noise) of seed `from` blended into that of seed `to` by `weight` in
/// [0, 1], each field kept at unit variance. Weight 0 gives the map of seed `from` alone.
struct SegmentationSeeds {
  uint64_t from = 0, to = 0;
  float weight = 0;
};

/// The seeds of frame `frame` of a sequence for an object whose maps draw on `object_seed`: the
/// layouts of keyframes `period` frames apart, blended in between, so that missed and
/// false-positive regions drift rather than jump from frame to frame.
SegmentationSeeds keyframeSeeds(uint64_t object_seed, int frame, int period);

/// simulateSegmentation() with a blend of two seeds' layouts; an absent object's blobs or
/// confusion come from the nearer seed.
cv::Mat simulateSegmentation(const SegmentationScene& scene, int target_obj_id,
                             const SegmentationNoiseParams& params, const SegmentationSeeds& seeds);

}  // namespace stocs
