#include "stocs_ros/scene_publisher/scene_publisher_params.h"

namespace stocs_ros {

const stocs::ParamSet<ScenePublisherParams>& ScenePublisherParams::schema() {
  using P = ScenePublisherParams;
  using stocs::ParamRange;
  static const stocs::ParamSet<P> schema =
      stocs::ParamSet<P>()
          .add(&P::dataset, "dataset", "", std::nullopt, "BOP dataset folder (required)")
          .add(&P::config, "config", "", std::nullopt,
               "the estimator's configuration: object names and ids, probability form (required)")
          .add(&P::split, "split", "", std::nullopt, "dataset split folder")
          .add(&P::scenes, "scenes", "", std::nullopt, "scene ids to play ([]: all)")
          .add(&P::images, "images", "", std::nullopt, "image ids to play ([]: all)")
          .add(&P::rate, "rate", "Hz", ParamRange::aboveUpTo(0, 100).orAlso(0),
               "frames per second; 0: the played sequences' own rate (scene_events.json), else "
               "2 / tracking.max_gap of the config (4 by default; 1 without tracking)")
          .add(&P::loop, "loop", "start again after the last frame")
          .add(&P::cache, "cache", "keep every decoded frame in memory for later passes")
          .add(&P::preload, "preload", "decode every frame before the first is published (cache)")
          .add(&P::frame_id, "frame_id", "", std::nullopt, "frame of every message")
          .choice(&P::probability_encoding, "probability_encoding",
                  {{"mono16", "mono16"}, {"mono8", "mono8"}, {"32FC1", "32FC1"}},
                  "probability images: mono16 (x input.uint16_scale), mono8 (x 255) or 32FC1")
          .add(&P::probability_source, "probability_source", "", std::nullopt,
               "where the maps come from, as `stocs estimate --prob` takes it")
          .add(&P::boundary, "boundary", "publish ~boundary");
  return schema;
}

}  // namespace stocs_ros
