// Google Benchmark of each StoCS stage on the two real-map frames (LM-O cat; packed bin dove), one
// thread, default parameters. Needs STOCS_DATASETS (the folder holding lmo-cat and rutgers-packed).
//   STOCS_DATASETS=../shared/datasets build/.../stocs_stage_benchmarks
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "benchmark_frames.h"
#include "stocs/estimation/stages/base_sampler.h"
#include "stocs/estimation/stages/congruent_set_matcher.h"
#include "stocs/estimation/stages/free_space_check.h"
#include "stocs/estimation/stages/lcp_scorer.h"
#include "stocs/geometry/rigid_fit.h"
#include "stocs/tracking/frame_tracker.h"

namespace stocs::bench {
namespace {

void softSegment(benchmark::State& state, const Frame& (*get)()) {
  const Frame& f = get();
  const PipelineParams p = benchmarkParams();
  const int threads = state.range(0) > 0
                          ? static_cast<int>(state.range(0))
                          : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  for (auto _ : state) {
    benchmark::DoNotOptimize(buildSoftSegment(f.cloud, f.probability, f.focal, p.segment, threads));
  }
  state.counters["points"] = static_cast<double>(f.segment.size());
}

void baseSampling(benchmark::State& state, const Frame& (*get)()) {
  const Frame& f = get();
  const BaseSampler sampler(f.segment, f.model.ppf_map, benchmarkParams().stocs.base);
  BaseSamplingScratch scratch;
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
  BaseSamplingScratch scratch;
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

constexpr uint64_t kFullEstimateSeeds = 10;

/// Runs the estimator on a frame, seed i % kFullEstimateSeeds on iteration i, with the benchmark
/// parameters as `configure` sets them. One seed's bases can be cheaper or dearer than the frame's
/// typical run, and code that changes the random stream must not look faster or slower for that
/// alone. The free-space check is the pipeline's (detectObject): it ranks the refined candidates
/// and guards the consensus stop.
template <class Configure>
void runEstimates(benchmark::State& state, const Frame& f, Configure&& configure) {
  const CameraIntrinsics camera = intrinsicsFromCloud(f.cloud);
  const PipelineParams defaults = benchmarkParams();
  const FreeSpaceCheck free_space(f.cloud, camera, defaults.stocs.free_space);
  std::vector<StocsEstimator> estimators;
  estimators.reserve(kFullEstimateSeeds);
  for (uint64_t seed = 0; seed < kFullEstimateSeeds; ++seed) {
    PipelineParams p = defaults;
    configure(p.stocs);
    p.stocs.seed = seed;
    estimators.emplace_back(f.model, p.stocs);
  }
  size_t i = 0;
  int bases = 0, draws = 0;
  for (auto _ : state) {
    const PoseEstimate e = estimators[i++ % kFullEstimateSeeds].search(f.segment, &free_space);
    bases += e.bases_tried;
    draws += e.base_draws;
    benchmark::DoNotOptimize(e);
  }
  state.counters["bases"] = benchmark::Counter(bases, benchmark::Counter::kAvgIterations);
  state.counters["draws"] = benchmark::Counter(draws, benchmark::Counter::kAvgIterations);
}

void fullEstimate(benchmark::State& state, const Frame& (*get)()) {
  runEstimates(state, get(), [&](StocsParams& p) {
    p.threads = static_cast<int>(state.range(0));    // 0: all cores
    if (state.range(1) == 0) p.consensus_bases = 0;  // 0: every base; 1: the default
  });
}

/// The low-latency settings of the side by side at equal accuracy: few bases, with and without
/// drawing failed bases again (StocsParams::base_draw_budget), on all cores.
void fewBases(benchmark::State& state, const Frame& (*get)()) {
  runEstimates(state, get(), [&](StocsParams& p) {
    p.threads = 0;
    p.bases = static_cast<int>(state.range(0));
    p.base_draw_budget = static_cast<int>(state.range(1));
  });
}

/// The whole per-object pipeline as the CLI, the side by side and the node run it (detectObject
/// with the frame's intrinsics: soft segment, instance regions where the frame has a boundary map,
/// free-space check, StoCS) at
/// the few bases of the side by side's equal-accuracy points, on all cores; seed i % 10 on
/// iteration i.
void pipeline(benchmark::State& state, const Frame& (*get)()) {
  const Frame& f = get();
  PipelineParams p = benchmarkParams();
  p.stocs.threads = 0;
  p.stocs.bases = static_cast<int>(state.range(0));
  const cv::Mat* boundary = f.boundary.empty() ? nullptr : &f.boundary;
  uint64_t i = 0;
  for (auto _ : state) {
    p.stocs.seed = i++ % kFullEstimateSeeds;
    benchmark::DoNotOptimize(
        detectObject(f.cloud, f.focal, f.probability, f.model, p, boundary, &f.camera));
  }
}

/// A frame of the demo's scene (six objects) tracked on all cores, every object tracked since the
/// previous frame: the first frame detects them (untimed), then each iteration tracks the same
/// image as the next frame at 30 Hz. The scene is static, so the refinements start at the right
/// pose: a moving scene costs a few ICP steps more. Arg: tracking.redetect_every (0: tracking
/// alone; 15: the default schedule of full detection). Counters: per frame, poses tracked and
/// objects detected in full.
void tracking(benchmark::State& state) {
  const SceneFrame& scene = demoScene();
  PipelineParams p = benchmarkParams();
  p.stocs.threads = 0;
  TrackingParams t;
  t.redetect_every = static_cast<int>(state.range(0));
  FrameTracker tracker(t);
  double stamp = 0;
  tracker.track(scene.frame, scene.objects, p, stamp);
  int tracked = 0, detections = 0;
  for (auto _ : state) {
    stamp += 1.0 / 30;
    const FrameTracking r = tracker.track(scene.frame, scene.objects, p, stamp);
    tracked += r.counts.tracked;
    detections += r.counts.detections;
  }
  state.counters["tracked"] = benchmark::Counter(tracked, benchmark::Counter::kAvgIterations);
  state.counters["detections"] = benchmark::Counter(detections, benchmark::Counter::kAvgIterations);
}

BENCHMARK(tracking)
    ->ArgName("redetect_every")
    ->Arg(0)
    ->Arg(15)
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(baseSampling, cat, cat)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(baseSampling, dove, dove)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(congruentSets, cat, cat)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(congruentSets, dove, dove)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(verification, cat, cat)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(verification, dove, dove)->Unit(benchmark::kMicrosecond);
// Per frame: the soft segment, the whole estimate (with every base, consensus:0, and with the
// default consensus stop, consensus:1) and the few-base settings. Each on one thread (CPU time per
// core) and, where threads:0 or no thread count is named, on all cores: process CPU time over all
// threads and wall time. A repetition of an estimate runs every seed once.
const bool kPerFrameRegistered = [] {
  auto onAllCores = [](benchmark::internal::Benchmark* b) {
    b->MeasureProcessCPUTime()->UseRealTime()->Unit(benchmark::kMillisecond);
  };
  const std::pair<std::string, const Frame& (*)()> frames[] = {
      {"cat", cat}, {"dove", dove}, {"box", box}};
  for (const auto& [frame, get] : frames) {
    const std::string soft = "softSegment/" + frame, full = "fullEstimate/" + frame;
    benchmark::RegisterBenchmark(soft.c_str(), softSegment, get)
        ->ArgName("threads")
        ->Arg(1)
        ->Unit(benchmark::kMillisecond);
    onAllCores(
        benchmark::RegisterBenchmark(soft.c_str(), softSegment, get)->ArgName("threads")->Arg(0));
    benchmark::RegisterBenchmark(full.c_str(), fullEstimate, get)
        ->ArgsProduct({{1}, {0, 1}})
        ->ArgNames({"threads", "consensus"})
        ->Iterations(kFullEstimateSeeds)
        ->Unit(benchmark::kMillisecond);
    onAllCores(benchmark::RegisterBenchmark(full.c_str(), fullEstimate, get)
                   ->ArgsProduct({{0}, {0, 1}})
                   ->ArgNames({"threads", "consensus"})
                   ->Iterations(kFullEstimateSeeds));
    onAllCores(benchmark::RegisterBenchmark(("fewBases/" + frame).c_str(), fewBases, get)
                   ->ArgsProduct({{5, 10, 20}, {0, 100}})
                   ->ArgNames({"bases", "draw_budget"})
                   ->Iterations(kFullEstimateSeeds));
    onAllCores(benchmark::RegisterBenchmark(("pipeline/" + frame).c_str(), pipeline, get)
                   ->ArgName("bases")
                   ->DenseRange(2, 5)
                   ->Iterations(10 * kFullEstimateSeeds));
  }
  return true;
}();

}  // namespace
}  // namespace stocs::bench

BENCHMARK_MAIN();
