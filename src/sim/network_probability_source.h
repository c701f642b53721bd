#pragma once
// "onnx:MODEL": probability maps from a segmentation network run on the dataset's rgb/ images.

#include <memory>
#include <string>

#include "stocs/sim/probability_source.h"

namespace stocs {

/// The network in `model` with the package network's settings (SegmentationNetworkParams'
/// defaults: channel k is obj_id k), on each frame's rgb/ image once. Throws InputError when the
/// model cannot be loaded. Keeps the last frame's maps: not for several threads at once.
std::unique_ptr<ProbabilitySource> makeNetworkProbabilitySource(const std::string& spec,
                                                                const std::string& model,
                                                                const BopDataset& dataset);

}  // namespace stocs
