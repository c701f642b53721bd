#pragma once
// The StoCS node's private ROS parameters, read through their schema (readSchemaParams) and listed
// in docs/parameters.md; everything else is in the configuration file they name.

#include <string>

#include "stocs/util/param_set.h"

namespace stocs_ros {

struct StocsNodeParams {
  std::string config;   ///< required
  std::string dataset;  ///< what $(dataset) in the configuration's paths stands for

  static const stocs::ParamSet<StocsNodeParams>& schema();
};

}  // namespace stocs_ros
