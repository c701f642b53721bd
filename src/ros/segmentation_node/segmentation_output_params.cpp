#include "stocs_ros/segmentation_node/segmentation_output_params.h"

namespace stocs_ros {

const stocs::ParamSet<SegmentationOutputParams>& SegmentationOutputParams::schema() {
  using P = SegmentationOutputParams;
  static const stocs::ParamSet<P> schema = stocs::ParamSet<P>().choice(
      &P::depth, "probability_depth", {{"32F", P::Depth::kFloat}, {"8U", P::Depth::kByte}},
      "published maps: 32F (32FC<n> probabilities) or 8U (8UC<n>, round(255 p): a quarter of the "
      "bytes; the StoCS node reads value / 255)");
  return schema;
}

}  // namespace stocs_ros
