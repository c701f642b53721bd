#include "stocs/tracking/tracking_params.h"

namespace stocs {

const ParamSet<TrackingParams>& TrackingParams::schema() {
  static const ParamSet<TrackingParams> schema =
      ParamSet<TrackingParams>()
          .add(&TrackingParams::enabled, "enabled",
               "track objects from frame to frame instead of detecting them in every frame")
          .flag("--track")
          .add(&TrackingParams::redetect_every, "redetect_every", "",
               ParamRange::closed(0, 1000000),
               "full detection every this many frames while tracked; 0: only when tracking fails")
          .flag("--redetect-every")
          .add(&TrackingParams::max_gap, "max_gap", "s", ParamRange::aboveUpTo(0, 3600),
               "a longer gap between input frames, or a stamp going back, ends every track")
          .flag("--max-gap")
          .add(&TrackingParams::velocity_damping, "velocity_damping", "", ParamRange::closed(0, 1),
               "share of the last velocity applied by the prediction; 0: the last pose")
          .flag("--velocity-damping")
          .add(&TrackingParams::roi_margin, "roi_margin", "", ParamRange::closed(0, 10),
               "a tracked object is segmented in its predicted box widened by this share")
          .flag("--roi-margin")
          .add(&TrackingParams::local_search, "local_search",
               "when tracking fails, search the object's box with StoCS before the whole image "
               "(stocs estimate --track; the node detects in the background)")
          .flag("--local-search")
          .add(&TrackingParams::match_distance, "match_distance", "", ParamRange::aboveUpTo(0, 10),
               "a detection continues a track within this share of the diameter (model centres)")
          .flag("--match-distance")
          .add(&TrackingParams::hold_hidden, "hold_hidden",
               "hold a track hidden behind a nearer surface (unpublished, followed on) rather than "
               "lose it; a follow moving it past the instance separation is not taken, a detection "
               "turning it only where the confidence prefers it")
          .flag("--hold-hidden");
  return schema;
}

void TrackingParams::validate() const {
  schema().validate(*this);
}

}  // namespace stocs
