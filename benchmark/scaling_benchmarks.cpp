// Time per object versus segment size and model size at a fixed number of bases (100, one thread).
// Google Benchmark fits the growth (BigO, RMS); issue 6 asks for no worse than linear in the
// segment size. Needs STOCS_DATASETS (see benchmark_frames.h).
//   STOCS_DATASETS=../shared/datasets build/.../stocs_scaling_benchmarks
#include <benchmark/benchmark.h>

#include <opencv2/imgproc.hpp>

#include "benchmark_frames.h"

namespace stocs::bench {
namespace {

/// The cat's probability map with every pixel within `margin` px of the object's box raised to at
/// least 0.3, as a sloppy network would: the segment grows with clutter around the object.
cv::Mat clutteredProbability(const cv::Mat& probability, int margin) {
  cv::Mat out = probability.clone();
  const cv::Rect object = cv::boundingRect(probability > 0.5f);
  const cv::Rect box = cv::Rect(object.x - margin, object.y - margin, object.width + 2 * margin,
                                object.height + 2 * margin) &
                       cv::Rect(0, 0, probability.cols, probability.rows);
  cv::Mat roi = out(box);
  cv::max(roi, 0.3, roi);
  return out;
}

void segmentSize(benchmark::State& state) {
  const Frame& f = cat();
  const PipelineParams p = benchmarkParams();
  const SoftSegment segment = buildSoftSegment(
      f.cloud, clutteredProbability(f.probability, static_cast<int>(state.range(0))), f.focal,
      p.segment);
  const StocsEstimator estimator(f.model, p.stocs);
  for (auto _ : state) benchmark::DoNotOptimize(estimator.search(segment));
  state.SetComplexityN(static_cast<int64_t>(segment.size()));
  state.counters["segment_points"] = static_cast<double>(segment.size());
}

void modelSize(benchmark::State& state) {
  const Frame& f = cat();
  PipelineParams p = benchmarkParams();
  p.model.sampling.sampling_ratio = static_cast<float>(state.range(0)) / 1000.0f;
  const PreparedModel model = prepareModelFile(f.model_file, 0.001f, p.model);
  const StocsEstimator estimator(model, p.stocs);
  for (auto _ : state) benchmark::DoNotOptimize(estimator.search(f.segment));
  state.SetComplexityN(static_cast<int64_t>(model.model.size()));
  state.counters["model_points"] = static_cast<double>(model.model.size());
}

BENCHMARK(segmentSize)
    ->Arg(0)
    ->Arg(20)
    ->Arg(40)
    ->Arg(80)
    ->Arg(160)
    ->Arg(320)
    ->Complexity()
    ->Unit(benchmark::kMillisecond);
// Poisson-disc radius in thousandths of the diameter: 80 (coarse) to 20 (about 4x the default 40's
// samples).
BENCHMARK(modelSize)->Arg(80)->Arg(60)->Arg(40)->Arg(30)->Arg(20)->Complexity()->Unit(
    benchmark::kMillisecond);

}  // namespace
}  // namespace stocs::bench

BENCHMARK_MAIN();
