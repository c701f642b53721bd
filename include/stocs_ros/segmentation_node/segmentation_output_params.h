#pragma once
// How the segmentation node publishes the network's maps (beside the network's own parameters,
// stocs::SegmentationNetworkParams, in the node's private namespace).

#include "stocs/util/param_set.h"

namespace stocs_ros {

struct SegmentationOutputParams {
  enum class Depth { kFloat, kByte };

  /// kFloat: 32FC<n> probabilities; kByte: 8UC<n> holding round(255 p), a quarter of the bytes
  /// to copy and send, which the StoCS node reads as p = value / 255.
  Depth depth = Depth::kFloat;

  static const stocs::ParamSet<SegmentationOutputParams>& schema();
};

}  // namespace stocs_ros
