#pragma once
// The frames the benchmarks run on, each loaded once: the real-map frames (LM-O cat; packed bin
// dove) from STOCS_DATASETS (the folder holding lmo-cat and rutgers-packed), and the box of the
// generated scene the node latency benchmark plays (scripts/bench_latency.sh: `stocs synth
// --objects 3 --distractors 2 --seed 1`), written to a temporary folder; and every object of the
// demo's scene (`stocs synth --objects 6 --distractors 2 --seed 1`) for tracking.

#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "stocs/estimation/frame.h"
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

/// Every object of a generated image, with its map, ready for the frame loop.
struct SceneFrame {
  stocs::Frame frame;
  std::map<int, PreparedModel> models;  ///< by object id, with the default preparation
  std::vector<FrameObject> objects;     ///< named by object id
  cv::Mat colour;  ///< the image's rgb/ (BGR), not set in `frame`: a benchmark opts in
};

/// Default parameters on one thread, so that times are per core.
PipelineParams benchmarkParams();

/// Throws std::runtime_error when STOCS_DATASETS is unset or the frame is missing.
const Frame& cat();
const Frame& dove();
const Frame& box();
/// The demo's scene: six objects and two distractors (seed 1), 640x480.
const SceneFrame& demoScene();

}  // namespace stocs::bench
