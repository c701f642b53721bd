#pragma once
// "geometric": probability maps from the depth image alone (geometric_segmentation.h), for objects
// no network knows.

#include <memory>

#include "stocs/segmentation/geometric_segmentation.h"
#include "stocs/sim/probability_source.h"

namespace stocs {

/// Each frame's depth image (depth/, scene_camera.json) segmented once; an object's map is the
/// union of the regions that can hold it, by the size of its model file (models/, millimetres).
/// load() throws InputError naming a model file it cannot read. Keeps the last frame's
/// segmentation: not for several threads at once.
std::unique_ptr<ProbabilitySource> makeGeometricProbabilitySource(
    const BopDataset& dataset, const GeometricSegmentationParams& params = {});

}  // namespace stocs
