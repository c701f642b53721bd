#pragma once
// The scene publisher's private parameters, read through their schema (readSchemaParams) and
// listed in docs/parameters.md.

#include <string>
#include <vector>

#include "stocs/util/param_set.h"

namespace stocs_ros {

struct ScenePublisherParams {
  std::string dataset;  ///< required
  std::string config;   ///< required
  std::string split = "test";
  std::vector<int> scenes, images;  ///< empty: all
  double rate = 0;                  ///< Hz; 0: the played sequences' own, else 2 / max_gap
  bool loop = true;
  bool cache = false;
  bool preload = false;
  std::string frame_id = "camera_optical_frame";
  std::string probability_encoding = "mono16";
  std::string probability_source = "real";
  bool boundary = true;

  static const stocs::ParamSet<ScenePublisherParams>& schema();
};

}  // namespace stocs_ros
