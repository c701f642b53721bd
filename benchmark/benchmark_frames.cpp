#include "benchmark_frames.h"

#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>

#include "stocs/io/bop_dataset.h"
#include "stocs/sim/synthetic_dataset.h"

namespace stocs::bench {
namespace {

const Frame& frame(const std::filesystem::path& dataset, int scene, int image, int object) {
  static std::map<std::filesystem::path, Frame> frames;
  auto it = frames.find(dataset);
  if (it != frames.end()) return it->second;
  const BopDataset ds(dataset);
  Frame f;
  const cv::Mat depth = ds.loadDepth(scene, image);
  const BopFrameCamera cam = ds.sceneCameras(scene).at(image);
  const CameraIntrinsics k = cam.intrinsics(depth.cols, depth.rows);
  f.cloud = cloudFromDepth(depth, k, cam.depth_scale / 1000);
  f.camera = k;
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

std::filesystem::path sharedDataset(const std::string& name) {
  const char* root = std::getenv("STOCS_DATASETS");
  if (!root) throw std::runtime_error("set STOCS_DATASETS to the folder holding " + name);
  return std::filesystem::path(root) / name;
}

/// The generated scene, written once per process and removed at exit.
std::filesystem::path generatedScene() {
  struct Scene {
    std::filesystem::path root =
        std::filesystem::temp_directory_path() / ("stocs_bench_scene_" + std::to_string(getpid()));
    Scene() {
      SyntheticDatasetParams p;
      p.layout.objects = 3;
      p.layout.distractors = 2;
      p.seed = 1;
      std::filesystem::remove_all(root);
      writeSyntheticDataset(root, p);
    }
    ~Scene() {
      std::error_code ignored;
      std::filesystem::remove_all(root, ignored);
    }
  };
  static const Scene scene;
  return scene.root;
}

}  // namespace

PipelineParams benchmarkParams() {
  PipelineParams p;
  p.stocs.threads = 1;
  return p;
}

const Frame& cat() {
  return frame(sharedDataset("lmo-cat"), 2, 3, 6);
}
const Frame& dove() {
  return frame(sharedDataset("rutgers-packed"), 0, 0, 1);
}
const Frame& box() {
  return frame(generatedScene(), 0, 0, 1);
}

}  // namespace stocs::bench
