#pragma once
// The demo recorder's private parameters, read through their schema (readSchemaParams) and
// listed in docs/parameters.md.

#include <string>

#include "stocs/util/param_set.h"

namespace stocs_ros {

struct DemoRecorderParams {
  std::string results;  ///< required
  int frames = 3;
  int scene = 0, image = 0;
  double timeout = 120;  ///< seconds

  static const stocs::ParamSet<DemoRecorderParams>& schema();
};

}  // namespace stocs_ros
