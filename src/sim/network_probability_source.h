#pragma once
// "onnx:MODEL" or "onnx:SETTINGS.yaml": probability maps from a segmentation network run on the
// dataset's rgb/ images.

#include <memory>
#include <string>

#include "stocs/sim/probability_source.h"

namespace stocs {

/// `file` is the ONNX model run with the package network's settings (SegmentationNetworkParams'
/// defaults: channel k is obj_id k), or a YAML settings file (.yaml, .yml) in
/// config/segmenter.yaml's format whose `model` names the ONNX file and whose `channels`, if set,
/// name obj_ids; the network runs on each frame's rgb/ image once. Throws InputError when the
/// settings are wrong or the model cannot be loaded. Keeps the last frame's maps: not for several
/// threads at once.
std::unique_ptr<ProbabilitySource> makeNetworkProbabilitySource(const std::string& spec,
                                                                const std::string& file,
                                                                const BopDataset& dataset);

}  // namespace stocs
