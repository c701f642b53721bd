// Google Benchmark of each StoCS stage on the two real-map frames (LM-O cat; packed bin dove), one
// thread, default parameters. Needs STOCS_DATASETS (the folder holding lmo-cat and rutgers-packed).
//   STOCS_DATASETS=../shared/datasets build/.../stocs_stage_benchmarks
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <opencv2/core.hpp>

#include "stocs/base_sampler.h"
#include "stocs/bop_dataset.h"
#include "stocs/congruent_set_matcher.h"
#include "stocs/lcp_scorer.h"
#include "stocs/pipeline.h"
#include "stocs/rigid_fit.h"

namespace stocs {
namespace {

struct Frame {
  OrganizedCloud cloud;
  float focal = 0;
  cv::Mat probability, boundary;
  PreparedModel model;
  SoftSegment segment;
};

PipelineParams benchmarkParams() {
  PipelineParams p;
  p.stocs.threads = 1;
  return p;
}

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
  f.model = prepareModelFile(ds.modelPath(object).string(), 0.001f, p.model);
  f.segment = buildSoftSegment(f.cloud, f.probability, f.focal, p.segment);
  if (!f.boundary.empty()) labelRegions(f.segment, f.boundary, depth.cols, depth.rows);
  return frames.emplace(dataset, std::move(f)).first->second;
}

const Frame& cat() {
  return frame("lmo-cat", 2, 3, 6);
}
const Frame& dove() {
  return frame("rutgers-packed", 0, 0, 1);
}

void softSegment(benchmark::State& state, const Frame& (*get)()) {
  const Frame& f = get();
  const PipelineParams p = benchmarkParams();
  for (auto _ : state)
    benchmark::DoNotOptimize(buildSoftSegment(f.cloud, f.probability, f.focal, p.segment));
  state.counters["points"] = static_cast<double>(f.segment.size());
}

void baseSampling(benchmark::State& state, const Frame& (*get)()) {
  const Frame& f = get();
  const BaseSampler sampler(f.segment, f.model.ppf_map, benchmarkParams().stocs.base);
  std::vector<std::pair<int, float>> scratch;
  uint64_t b = 0;
  for (auto _ : state) {
    Rng rng(streamSeed(0, b++));
    benchmark::DoNotOptimize(sampler.sample(rng, scratch));
  }
}

void congruentSets(benchmark::State& state, const Frame& (*get)()) {
  const Frame& f = get();
  const PipelineParams p = benchmarkParams();
  const BaseSampler sampler(f.segment, f.model.ppf_map, p.stocs.base);
  const CongruentSetMatcher matcher(f.model, p.stocs.congruent);
  std::vector<std::pair<int, float>> scratch;
  std::vector<std::array<Eigen::Vector3f, 4>> points, normals;
  for (uint64_t b = 0; points.size() < 100 && b < 1000; ++b) {
    Rng rng(streamSeed(0, b));
    if (const auto base = sampler.sample(rng, scratch)) {
      points.emplace_back();
      normals.emplace_back();
      for (int k = 0; k < 4; ++k) {
        points.back()[k] = f.segment.points[(*base)[k]];
        normals.back()[k] = f.segment.normals[(*base)[k]];
      }
    }
  }
  std::vector<CongruentSet> sets;
  size_t i = 0, total = 0;
  Rng rng(1);
  for (auto _ : state) {
    total += matcher.find(points[i % points.size()], normals[i % points.size()], rng, sets);
    ++i;
  }
  state.counters["sets_per_base"] = static_cast<double>(total) / static_cast<double>(i);
}

void verification(benchmark::State& state, const Frame& (*get)()) {
  // Scores of hypotheses against the segment, without early stop: the cost of one full LCP.
  const Frame& f = get();
  const LcpScorer scorer(f.segment, benchmarkParams().stocs.lcp);
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.translation() = f.segment.points[f.segment.size() / 2];
  for (auto _ : state) benchmark::DoNotOptimize(scorer.score(f.model.model, pose));
  state.counters["model_points"] = static_cast<double>(f.model.model.size());
}

void fullEstimate(benchmark::State& state, const Frame& (*get)()) {
  const Frame& f = get();
  const PipelineParams p = benchmarkParams();
  const StocsEstimator estimator(f.model, p.stocs);
  for (auto _ : state) benchmark::DoNotOptimize(estimator.estimate(f.segment));
}

BENCHMARK_CAPTURE(softSegment, cat, cat)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(softSegment, dove, dove)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(baseSampling, cat, cat)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(baseSampling, dove, dove)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(congruentSets, cat, cat)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(congruentSets, dove, dove)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(verification, cat, cat)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(verification, dove, dove)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(fullEstimate, cat, cat)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(fullEstimate, dove, dove)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace stocs

BENCHMARK_MAIN();
