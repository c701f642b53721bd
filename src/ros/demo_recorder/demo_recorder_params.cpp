#include "stocs_ros/demo_recorder/demo_recorder_params.h"

namespace stocs_ros {

const stocs::ParamSet<DemoRecorderParams>& DemoRecorderParams::schema() {
  using P = DemoRecorderParams;
  using stocs::ParamRange;
  static const stocs::ParamSet<P> schema =
      stocs::ParamSet<P>()
          .add(&P::results, "results", "", std::nullopt,
               "the BOP results file written with the last frame's poses (required)")
          .add(&P::frames, "frames", "", ParamRange::closed(1, 1000),
               "frames of estimates to wait for")
          .add(&P::scene, "scene", "", std::nullopt, "scene id of the played frame, in the results")
          .add(&P::image, "image", "", std::nullopt, "image id of the played frame, in the results")
          .add(&P::timeout, "timeout", "s", ParamRange::aboveUpTo(0, 3600),
               "how long to wait for the frames before giving up");
  return schema;
}

}  // namespace stocs_ros
