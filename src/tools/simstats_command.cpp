// `stocs simstats`: pixel precision and recall at a threshold of the segmentation simulator's
// presets, of the dataset's own prob/ maps (real network maps in ../shared/datasets) and of ONNX
// segmentation networks (--network, on rgb/), against the visible ground-truth masks, as one
// markdown table (the preset calibration in docs/simulator.md); --recall-floor also counts the
// single maps below a recall floor, as a one-image test would see them.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <map>
#include <opencv2/core.hpp>
#include <optional>
#include <set>

#include "commands.h"
#include "stocs/eval/segmentation_metrics.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/sim/ground_truth_masks.h"
#include "stocs/sim/probability_source.h"
#include "stocs/sim/segmentation_simulator.h"

namespace stocs::tools {
namespace {

struct SimstatsOptions {
  std::vector<std::string> datasets;
  std::vector<std::string> presets = segmentationPresetNames();
  std::vector<std::string> networks;
  int seeds = 3;
  float threshold = 0.5f;
  bool per_object = false;
  std::optional<double> recall_floor;
};

struct Row {
  PixelCounts counts;
  int maps = 0;
  int maps_at_or_below_floor = 0;
};

/// Rows in the order they were first counted, by what made the maps (and the object).
struct Rows {
  std::optional<double> recall_floor;
  std::vector<std::string> order;
  std::map<std::string, Row> rows;

  void add(const std::string& key, const PixelCounts& counts) {
    if (rows.find(key) == rows.end()) order.push_back(key);
    Row& row = rows[key];
    row.counts += counts;
    ++row.maps;
    if (recall_floor && counts.recall() <= *recall_floor) ++row.maps_at_or_below_floor;
  }
};

/// One source of maps and the row it counts in.
struct LabelledSource {
  std::string label;
  std::unique_ptr<ProbabilitySource> source;
};

std::vector<LabelledSource> mapSources(const BopDataset& dataset, const SimstatsOptions& o) {
  std::vector<LabelledSource> sources;
  for (int seed = 1; seed <= o.seeds; ++seed) {
    for (const std::string& preset : o.presets) {
      sources.push_back(
          {"simulator, " + preset, makeProbabilitySource("simonly:" + preset, dataset, seed)});
    }
  }
  for (const std::string& model : o.networks) {
    sources.push_back({"network " + std::filesystem::path(model).filename().string(),
                       makeProbabilitySource("onnx:" + model, dataset, 0)});
  }
  return sources;
}

/// The visible mask of every instance of `obj` in the frame.
cv::Mat objectMask(const SegmentationScene& frame, int obj) {
  cv::Mat target(frame.labels.size(), CV_8UC1, cv::Scalar(0));
  for (size_t i = 0; i < frame.obj_ids.size(); ++i) {
    if (frame.obj_ids[i] == obj) target.setTo(255, frame.labels == static_cast<int>(i) + 1);
  }
  return target;
}

void printRow(const std::string& dataset, const std::string& masks, const std::string& source,
              const Row& row, bool with_floor) {
  fmt::print("| {} | {} | {} | {} | {:.1f}% | {:.1f}% |", dataset, masks, source, row.maps,
             100 * row.counts.precision(), 100 * row.counts.recall());
  if (with_floor) fmt::print(" {} |", row.maps_at_or_below_floor);
  fmt::print("\n");
}

void measureDataset(const std::string& root, const SimstatsOptions& o) {
  const BopDataset dataset(root);
  const GroundTruthMasks masks(dataset);
  const std::string name = std::filesystem::path(root).filename().string();
  Rows rows{o.recall_floor, {}, {}};
  std::set<std::string> mask_kinds;
  const std::vector<LabelledSource> sources = mapSources(dataset, o);
  for (int scene : dataset.sceneIds()) {
    for (const auto& [im, instances] : dataset.sceneGroundTruth(scene)) {
      const SegmentationScene frame = masks.frame(scene, im);
      mask_kinds.insert(masks.hasMaskVisib(scene, im, instances.size()) ? "mask_visib"
                                                                        : "rendered");
      const std::set<int> objects(frame.obj_ids.begin(), frame.obj_ids.end());
      for (int obj : objects) {
        const cv::Mat target = objectMask(frame, obj);
        const std::string suffix = o.per_object ? fmt::format(", obj {}", obj) : "";
        if (std::filesystem::exists(dataset.probabilityPath(scene, im, obj))) {
          rows.add(
              "dataset's prob/ maps" + suffix,
              countSegmentPixels(dataset.loadProbability(scene, im, obj), target, o.threshold));
        }
        for (const LabelledSource& s : sources) {
          rows.add(s.label + suffix,
                   countSegmentPixels(s.source->load(scene, im, obj), target, o.threshold));
        }
      }
    }
  }
  const std::string kinds = fmt::format("{}", fmt::join(mask_kinds, ", "));
  for (const std::string& key : rows.order) {
    printRow(name, kinds, key, rows.rows.at(key), o.recall_floor.has_value());
  }
}

int runSimstats(const SimstatsOptions& o) {
  for (const std::string& preset : o.presets) segmentationPreset(preset);  // names checked first
  fmt::print("| dataset | masks | maps from | maps | precision | recall |");
  if (o.recall_floor) fmt::print(" maps with recall <= {} |", *o.recall_floor);
  fmt::print("\n|---|---|---|---|---|---|{}\n", o.recall_floor ? "---|" : "");
  for (const std::string& root : o.datasets) measureDataset(root, o);
  return 0;
}

}  // namespace

Command registerSimstats(CLI::App& app) {
  auto o = std::make_shared<SimstatsOptions>();
  CLI::App* cmd = app.add_subcommand(
      "simstats",
      "Pixel precision and recall of the segmentation simulator's presets and of the dataset's "
      "prob/ maps against the visible ground-truth masks");
  cmd->add_option("--dataset", o->datasets, "BOP dataset folder (repeatable)")->required();
  cmd->add_option("--presets", o->presets, "Simulator presets, comma-separated")->delimiter(',');
  cmd->add_option("--network", o->networks,
                  "ONNX segmentation network (the package's settings) or settings YAML naming "
                  "one, as --prob onnx: takes it, run on rgb/ (repeatable)");
  cmd->add_flag("--per-object", o->per_object, "One row per object");
  cmd->add_option("--seeds", o->seeds, "Simulated maps per object: seeds 1..N")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--threshold", o->threshold, "Probability above which a pixel is in the segment")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--recall-floor", o->recall_floor,
                  "Also count the maps (an object in one image) whose own recall is at or below "
                  "this")
      ->check(CLI::Range(0.0, 1.0));
  return {cmd, [o] { return runSimstats(*o); }};
}

}  // namespace stocs::tools
