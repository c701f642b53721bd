#include "stocs_ros/stocs_node/stocs_node_params.h"

namespace stocs_ros {

const stocs::ParamSet<StocsNodeParams>& StocsNodeParams::schema() {
  using P = StocsNodeParams;
  static const stocs::ParamSet<P> schema =
      stocs::ParamSet<P>()
          .add(&P::config, "config", "", std::nullopt,
               "the configuration file (YAML, keys above; required)")
          .add(&P::dataset, "dataset", "", std::nullopt,
               "the BOP dataset folder that $(dataset) in the configuration's paths stands for "
               "(the launch files' dataset argument)");
  return schema;
}

}  // namespace stocs_ros
