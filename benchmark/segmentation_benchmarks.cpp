// Google Benchmark of the segmentation node's stages with the package's network
// (models/segmenter.onnx) on a 640x480 colour image: the network with its activation at the
// output's size (outputMaps), the six objects' maps upsampled to the image into one buffer as
// 32-bit or 8-bit (what the node publishes), and the whole segment() (all seven maps, float).
// Then the segmentation from depth alone on the demo's generated 640x480 frame (six objects, two
// distractors): the regions (geometricSegment), and the regions with the six objects' maps
// (geometricMaps, what `--prob geometric` costs a frame), without and with the colour image.
//   build/.../stocs_segmentation_benchmarks
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>

#include "benchmark_frames.h"
#include "stocs/segmentation/geometric_segmentation.h"
#include "stocs/segmentation/segmentation_network.h"

namespace stocs::bench {
namespace {

const SegmentationNetwork& network() {
  static const SegmentationNetwork net = [] {
    SegmentationNetworkParams p;
    p.model = STOCS_SEGMENTER_MODEL;
    return SegmentationNetwork(p);
  }();
  return net;
}

const cv::Mat& colourImage() {
  static const cv::Mat image = [] {
    cv::Mat m(480, 640, CV_8UC3);
    cv::randu(m, cv::Scalar::all(0), cv::Scalar::all(256));
    return m;
  }();
  return image;
}

void outputMaps(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(network().outputMaps(colourImage()));
}

/// Arg: the depth of the published maps (CV_32F or CV_8U).
void upsampleObjects(benchmark::State& state) {
  const cv::Mat maps = network().outputMaps(colourImage());
  const int depth = static_cast<int>(state.range(0));
  cv::Mat out;
  for (auto _ : state) {
    SegmentationNetwork::upsample(maps, {1, 2, 3, 4, 5, 6}, colourImage().size(), depth, out);
    benchmark::DoNotOptimize(out.data);
  }
  state.counters["MB"] = static_cast<double>(out.total() * out.elemSize()) / 1e6;
}

void segment(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(network().segment(colourImage()));
}

void geometricSegment(benchmark::State& state) {
  const stocs::Frame& frame = demoScene().frame;
  GeometricSegmenter segmenter;
  for (auto _ : state) {
    benchmark::DoNotOptimize(segmenter.segment(frame.cloud, *frame.camera).regions.data());
  }
}

/// Arg: 1 with the image's colour (each region's colour histogram), 0 without.
void geometricMaps(benchmark::State& state) {
  const SceneFrame& scene = demoScene();
  stocs::Frame frame = scene.frame;
  if (state.range(0)) frame.colour = scene.colour;
  GeometricSegmenter segmenter;
  for (auto _ : state) {
    benchmark::DoNotOptimize(setGeometricProbabilities(frame, scene.objects, segmenter).planes);
  }
  state.counters["objects"] = static_cast<double>(scene.objects.size());
}

BENCHMARK(outputMaps)->MeasureProcessCPUTime()->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(upsampleObjects)
    ->ArgName("depth")
    ->Arg(CV_32F)
    ->Arg(CV_8U)
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(segment)->MeasureProcessCPUTime()->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(geometricSegment)->MeasureProcessCPUTime()->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(geometricMaps)
    ->ArgName("colour")
    ->Arg(0)
    ->Arg(1)
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace stocs::bench

BENCHMARK_MAIN();
