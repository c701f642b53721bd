#pragma once
// The frames the benchmarks run on, each loaded once: the real-map frames (LM-O cat; packed bin
// dove) from STOCS_DATASETS (the folder holding lmo-cat and rutgers-packed), and the box of the
// generated scene the node latency benchmark plays (scripts/bench_latency.sh: `stocs synth
// --objects 3 --distractors 2 --seed 1`), written to a temporary folder.

#include <opencv2/core.hpp>
#include <string>

#include "stocs/estimation/pipeline.h"

namespace stocs::bench {

struct Frame {
  OrganizedCloud cloud;
  CameraIntrinsics camera;
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
const Frame& box();

}  // namespace stocs::bench
