#include "benchmark_frames.h"

#include <cstdlib>
#include <filesystem>
#include <map>

#include "stocs/bop_dataset.h"

namespace stocs::bench {
namespace {

const Frame& frame(const std::string& dataset, int scene, int image, int object) {
  static std::map<std::string, Frame> frames;
  auto it = frames.find(dataset);
  if (it != frames.end()) return it->second;
  const char* root = std::getenv("STOCS_DATASETS");
  if (!root) throw std::runtime_error("set STOCS_DATASETS to the folder holding " + dataset);
  const BopDataset ds(std::filesystem::path(root) / dataset);
  Frame f;
  const cv::Mat depth = ds.loadDepth(scene, image);
  const BopFrameCamera cam = ds.sceneCameras(scene).at(image);
  const CameraIntrinsics k = cam.intrinsics(depth.cols, depth.rows);
  f.cloud = cloudFromDepth(depth, k, cam.depth_scale / 1000);
  f.focal = static_cast<float>(k.fx);
  f.probability = ds.loadProbability(scene, image, object);
  f.boundary = ds.loadBoundary(scene, image);
  const PipelineParams p = benchmarkParams();
  f.model_file = ds.modelPath(object).string();
  f.model = prepareModelFile(f.model_file, 0.001f, p.model);
  f.segment = buildSoftSegment(f.cloud, f.probability, f.focal, p.segment);
  if (!f.boundary.empty()) labelRegions(f.segment, f.boundary, depth.cols, depth.rows);
  return frames.emplace(dataset, std::move(f)).first->second;
}

}  // namespace

PipelineParams benchmarkParams() {
  PipelineParams p;
  p.stocs.threads = 1;
  return p;
}

const Frame& cat() {
  return frame("lmo-cat", 2, 3, 6);
}
const Frame& dove() {
  return frame("rutgers-packed", 0, 0, 1);
}

}  // namespace stocs::bench
