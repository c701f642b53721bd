#pragma once
// Ground-truth detections made to err the way a real network does, for measuring how StoCS fares
// on each segmentation input form (`stocs estimate --prob masks:perturbed`, boxes:perturbed, ...).

#include <cstdint>
#include <vector>

#include "stocs/io/segmentation_inputs.h"
#include "stocs/sim/segmentation_simulator.h"

namespace stocs {

/// The instance masks a network could emit for object `obj_id`: the segmentation simulator's map
/// (missed parts, bleeding, false positives on neighbours and look-alikes, class confusion for an
/// absent object) thresholded at 0.5 and split into connected parts of at least 20 pixels, each
/// scored by the map's mean over it plus a uniform noise of +-0.15 (kept in [0.05, 1]).
std::vector<InstanceMask> perturbedMasks(const SegmentationScene& scene, int obj_id,
                                         const SegmentationNoiseParams& params, uint64_t seed);

/// `box` shifted by up to 15% of its size along each axis, each side moved out by up to 20% of
/// the size (a loose box), and scored uniformly in [0.5, 1]; the same for the same seed.
BoxDetection perturbedBox(const BoxDetection& box, uint64_t seed);

}  // namespace stocs
