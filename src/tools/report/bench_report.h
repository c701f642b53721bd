#pragma once
// What `stocs bench` measured, and the report it writes from it: markdown and CSV tables (method x
// dataset, segmentation-threshold, time-budget and base-count sweeps, speed at equal accuracy),
// per-target CSV and PNG plots.

#include <filesystem>
#include <string>
#include <vector>

#include "child_process.h"
#include "stocs/estimation/stages/pose_confidence.h"
#include "stocs/eval/dataset_evaluation.h"

namespace stocs::tools {

/// One dataset with one probability source: what every method runs on.
struct BenchInput {
  std::string dataset_name;       ///< folder name
  std::string source;             ///< probability source spec
  std::filesystem::path dataset;  ///< BOP folder (a converted copy for PCD scenes)
  std::vector<Target> targets;

  std::string name() const { return dataset_name + "/" + source; }
  /// name() usable in file names.
  std::string tag() const;
};

enum class Sweep { kNone, kThreshold, kBudget, kBases };

/// One child run of `stocs estimate`: a method on an input, at defaults or at one sweep value.
struct BenchRun {
  size_t input = 0;
  std::string method;
  Sweep sweep = Sweep::kNone;
  double value = 0;  ///< segmentation threshold, time budget (s) or bases; unused for kNone
  std::filesystem::path results, per_object, log;

  ChildOutcome child;
  std::string failure;  ///< why the run produced no (or unusable) results; empty if ok
  std::vector<TargetResult> targets;  ///< every target of the input, missing ones included
  std::vector<double> seconds;        ///< per target, NaN where the run did not report it
  std::vector<double> cpu_seconds;    ///< the same for the process's CPU time

  /// "stocs on lmo-cat/real, threshold 0.3".
  std::string label(const std::vector<BenchInput>& inputs) const;
};

struct BenchData {
  std::vector<BenchInput> inputs;
  std::vector<std::string> methods;
  std::vector<std::string> swept_methods;  ///< the methods run in the sweeps
  std::vector<double> thresholds;
  std::vector<double> budgets;
  std::vector<double> base_counts;  ///< ascending
  std::vector<BenchRun> runs;
  std::vector<std::string> notes;  ///< e.g. inputs skipped for want of targets
  std::string command;             ///< the command line, for the report
  bool warm = true;                ///< every run began with an untimed estimate (--warm-up)
  int repeats = 1;                 ///< every image processed this many times (--repeats)
  /// Score threshold of the confidence columns: the estimation's default min_confidence.
  double min_confidence = ConfidenceParams().min_confidence;
};

/// Writes into `out`: results.md, summary.csv, targets.csv, threshold_sweep.csv, budget_sweep.csv,
/// bases_sweep.csv and equal_accuracy.csv (when swept), and with `plots` plots/*.png (see
/// line_plot.h).
void writeBenchReport(const BenchData& data, const std::filesystem::path& out, bool plots);

}  // namespace stocs::tools
