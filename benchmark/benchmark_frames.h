#pragma once
// The real-map frames the benchmarks run on (LM-O cat; packed bin dove), loaded once from
// STOCS_DATASETS (the folder holding lmo-cat and rutgers-packed).

#include <opencv2/core.hpp>
#include <string>

#include "stocs/pipeline.h"

namespace stocs::bench {

struct Frame {
  OrganizedCloud cloud;
  float focal = 0;
  cv::Mat probability, boundary;
  std::string model_file;  ///< metres = file units / 1000
  PreparedModel model;     ///< with the default preparation
  SoftSegment segment;     ///< with the default segmentation, regions applied
};

/// Default parameters on one thread, so that times are per core.
PipelineParams benchmarkParams();

/// Throws std::runtime_error when STOCS_DATASETS is unset or the frame is missing.
const Frame& cat();
const Frame& dove();

}  // namespace stocs::bench
