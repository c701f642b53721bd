#include "stocs/io/segmentation_inputs.h"

namespace stocs {

const ParamSet<SegmentationInputParams>& SegmentationInputParams::schema() {
  using P = SegmentationInputParams;
  static const ParamSet<P> schema =
      ParamSet<P>()
          .add(&P::mask_border_px, "mask_border_px", "px", ParamRange::closed(0, 100),
               "a mask's border is blurred by a Gaussian of this deviation; 0: hard edges")
          .add(&P::mask_inside_floor, "mask_inside_floor", "", ParamRange::closed(0, 1),
               "a mask pixel keeps at least this share of the mask's score after the blur")
          .add(&P::mask_outside_floor, "mask_outside_floor", "", ParamRange::fromBelow(0, 1),
               "every pixel gets at least this probability (masks and labels)")
          .add(&P::box_edge_level, "box_edge_level", "", ParamRange::closed(0, 1),
               "share of a box's score left at its edge")
          .add(&P::box_core, "box_core", "", ParamRange::fromBelow(0, 1),
               "share of a box's half-size around its centre with the full score");
  return schema;
}

void SegmentationInputParams::validate() const {
  schema().validate(*this);
}

}  // namespace stocs
