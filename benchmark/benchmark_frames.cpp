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

/// A generated scene of `objects` objects and two distractors (seed 1), written to a temporary
/// folder; removed at exit.
struct GeneratedScene {
  std::filesystem::path root;
  explicit GeneratedScene(int objects)
      : root(std::filesystem::temp_directory_path() /
             ("stocs_bench_scene_" + std::to_string(objects) + "_" + std::to_string(getpid()))) {
    SyntheticDatasetParams p;
    p.layout.objects = objects;
    p.layout.distractors = 2;
    p.seed = 1;
    std::filesystem::remove_all(root);
    writeSyntheticDataset(root, p);
  }
  ~GeneratedScene() {
    std::error_code ignored;
    std::filesystem::remove_all(root, ignored);
  }
};

/// The generated scene of the latency benchmark, written once per process.
std::filesystem::path generatedScene() {
  static const GeneratedScene scene(3);
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

const SceneFrame& demoScene() {
  static const GeneratedScene scene(6);
  static const SceneFrame loaded = [] {
    const BopDataset ds(scene.root);
    SceneFrame s;
    const cv::Mat depth = ds.loadDepth(0, 0);
    const BopFrameCamera cam = ds.sceneCameras(0).at(0);
    s.frame = stocs::Frame::fromDepth(depth, cam.intrinsics(depth.cols, depth.rows),
                                      cam.depth_scale / 1000);
    s.colour = ds.loadColour(0, 0, depth.size());
    const std::map<int, std::vector<BopGtInstance>> truth = ds.sceneGroundTruth(0);
    for (const BopGtInstance& g : truth.at(0)) {
      const std::string name = std::to_string(g.obj_id);
      s.frame.probabilities[name] = ds.loadProbability(0, 0, g.obj_id);
      s.models[g.obj_id] =
          prepareModelFile(ds.modelPath(g.obj_id).string(), 0.001f, benchmarkParams().model);
    }
    for (const auto& [id, model] : s.models) s.objects.push_back({std::to_string(id), &model});
    return s;
  }();
  return loaded;
}

}  // namespace stocs::bench
