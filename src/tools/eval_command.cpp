// `stocs eval`: the metrics of BOP results files against their datasets' ground truth, per object,
// per dataset and overall, as markdown and CSV.
#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <iterator>
#include <map>

#include "cli_options.h"
#include "commands.h"
#include "report/confidence_report.h"
#include "report/coverage_report.h"
#include "report/eval_report.h"
#include "stocs/eval/dataset_evaluation.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/sim/probability_source.h"
#include "stocs/util/error.h"

namespace stocs::tools {
namespace {

struct EvalOptions {
  std::vector<std::string> datasets;
  std::vector<std::string> results;
  std::vector<std::string> targets;
  std::string split = "test";
  std::vector<int> scenes;
  std::vector<int> objects;
  std::string prob;
  double min_confidence = ConfidenceParams().min_confidence;  ///< the estimation's default
  std::string markdown;
  std::string csv;
  std::string targets_csv;
  std::string reliability_plot;
  std::vector<std::string> per_object;
};

/// The targets of dataset `i`: its --targets file's, else every selected object of scene_gt.json
/// (with a map from --prob when given).
std::vector<Target> evalTargets(const EvalOptions& o, size_t i, const BopDataset& dataset) {
  std::vector<Target> targets;
  if (!o.targets.empty()) {
    targets = targetsFromFile(dataset, o.targets[i], o.scenes, o.objects);
  } else {
    std::unique_ptr<ProbabilitySource> source;
    if (!o.prob.empty()) source = makeProbabilitySource(o.prob, dataset, 0);
    targets = listTargets(dataset, o.scenes, o.objects, source.get());
  }
  if (targets.empty()) {
    throw InputError(fmt::format("dataset {}: no target among the selected scenes and objects{}",
                                 o.datasets[i],
                                 !o.targets.empty() ? " in " + o.targets[i]
                                 : o.prob.empty()   ? ""
                                                    : " with a map from source '" + o.prob + "'"));
  }
  return targets;
}

/// The summary table: accuracy over the targets whose object is present, confidence over all.
class EvalTable {
 public:
  explicit EvalTable(double min_confidence) : min_confidence_(min_confidence), table_(header()) {}

  /// A row; returns its confidence metrics.
  ConfidenceMetrics add(const std::string& results, const std::string& dataset,
                        const std::string& object, const std::vector<TargetResult>& targets) {
    std::vector<TargetResult> present;
    std::copy_if(targets.begin(), targets.end(), std::back_inserter(present),
                 [](const TargetResult& t) { return !t.absent(); });
    const ConfidenceMetrics confidence = confidenceMetrics(scoredTargets(targets), min_confidence_);
    std::vector<Cell> row = {textCell(results), textCell(dataset), textCell(object)};
    for (const Cell& c : metricCells(summarize(errorsOf(present)))) row.push_back(c);
    for (const Cell& c : confidenceCells(confidence)) row.push_back(c);
    table_.add(row);
    return confidence;
  }

  const ReportTable& table() const { return table_; }

 private:
  static std::vector<Cell> header() {
    std::vector<Cell> h = {textCell("results"), textCell("dataset"), textCell("object")};
    for (const Cell& c : metricHeader()) h.push_back(c);
    for (const Cell& c : confidenceHeader()) h.push_back(c);
    return h;
  }

  double min_confidence_;
  ReportTable table_;
};

void checkPairs(const EvalOptions& o) {
  if (o.datasets.size() != o.results.size()) {
    throw InputError(
        fmt::format("--dataset and --results come in pairs: got {} datasets and {} "
                    "results files",
                    o.datasets.size(), o.results.size()));
  }
  if (!o.targets.empty() && o.targets.size() != o.datasets.size()) {
    throw InputError(fmt::format("--targets takes one file per --dataset: got {} for {} datasets",
                                 o.targets.size(), o.datasets.size()));
  }
  if (!o.per_object.empty() && o.per_object.size() != o.results.size()) {
    throw InputError(fmt::format("--per-object and --results come in pairs: got {} and {}",
                                 o.per_object.size(), o.results.size()));
  }
}

int runEval(const EvalOptions& o) {
  checkPairs(o);
  EvalTable table(o.min_confidence);
  std::vector<LabelledTarget> rows;
  std::vector<TargetResult> everything;
  std::vector<std::pair<std::string, ConfidenceMetrics>> reliability;
  std::string notes;
  for (size_t i = 0; i < o.datasets.size(); ++i) {
    const BopDataset dataset(o.datasets[i], o.split);
    const std::string name = datasetName(dataset.root());
    const std::vector<Target> targets = evalTargets(o, i, dataset);
    DatasetEvaluator evaluator(dataset);
    const ResultsEvaluation ev =
        evaluator.evaluate(targets, readBopResults(o.results[i]), o.results[i]);
    std::map<int, std::vector<TargetResult>> per_object;
    for (const TargetResult& t : ev.targets) {
      per_object[t.target.obj_id].push_back(t);
      rows.push_back({{o.results[i], name}, t});
      everything.push_back(t);
    }
    for (const auto& [obj, targets_of_obj] : per_object) {
      table.add(o.results[i], name, std::to_string(obj), targets_of_obj);
    }
    reliability.emplace_back(o.results[i], table.add(o.results[i], name, "all", ev.targets));
    if (!o.per_object.empty())
      notes += coverageNote(o.results[i], o.per_object[i], ev.targets, dataset);
    if (ev.duplicates || ev.not_targets) {
      notes += fmt::format(
          "- {}: {} rows beyond a target's highest-scoring one and {} rows for objects that are "
          "not targets were ignored.\n",
          o.results[i], ev.duplicates, ev.not_targets);
    }
  }
  const ConfidenceMetrics overall = o.datasets.size() > 1
                                        ? table.add("all", "all", "all", everything)
                                        : reliability.back().second;

  const std::string markdown = table.table().markdown() + "\n" + metricLegend() +
                               "Accuracy columns count the targets whose object is present.\n\n" +
                               confidenceLegend(o.min_confidence) +
                               (notes.empty() ? "" : "\n" + notes) + "\nReliability (" +
                               (o.datasets.size() > 1 ? "all results" : o.results[0]) + "):\n\n" +
                               reliabilityMarkdown(overall);
  if (o.markdown.empty()) {
    std::cout << markdown;
  } else {
    writeTextFile(o.markdown, markdown);
  }
  if (!o.csv.empty()) writeTextFile(o.csv, table.table().csv());
  if (!o.targets_csv.empty())
    writeTextFile(o.targets_csv, targetsCsv({"results", "dataset"}, rows));
  if (!o.reliability_plot.empty()) {
    renderPlot(reliabilityPlot("Reliability of the score", reliability), o.reliability_plot);
  }
  return 0;
}

}  // namespace

Command registerEval(CLI::App& app) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* cmd = app.add_subcommand(
      "eval",
      "Pose metrics of BOP results against ground truth (ADD, ADD-S, AUC, MSSD, APC errors)");
  cmd->add_option("--dataset", o->datasets, "BOP dataset folder; repeat, one per --results")
      ->required();
  cmd->add_option("--results", o->results, "BOP results CSV of the --dataset at the same position")
      ->required();
  addSelectionOptions(*cmd, o->split, o->scenes, o->objects);
  cmd->add_option("--targets", o->targets,
                  "BOP targets file (test_targets_bop19.json) of the --dataset at the same "
                  "position: evaluate exactly these targets; a pose for one with inst_count 0 "
                  "(an absent object) is a false positive");
  cmd->add_option("--prob", o->prob,
                  "Only targets with a probability map from this source (as `stocs estimate "
                  "--prob`); default: every object of scene_gt.json");
  cmd->add_option("--min-confidence", o->min_confidence,
                  "Score threshold of the precision, recall, absent-posed and correct-rejected "
                  "columns");
  cmd->add_option("--reliability-plot", o->reliability_plot,
                  "Reliability plot (PNG, needs gnuplot): share of correct poses against the "
                  "mean score of each of 10 score bins, one line per results file");
  cmd->add_option("--markdown", o->markdown, "Markdown report file (default: standard output)");
  cmd->add_option("--csv", o->csv, "Summary rows as CSV");
  cmd->add_option("--per-object", o->per_object,
                  "`stocs estimate --per-object` file of each --results: reports the share of true "
                  "errors of correct poses inside the covariances' 50% and 90% ellipsoids");
  cmd->add_option("--targets-csv", o->targets_csv, "One CSV row per target with every error");
  return {cmd, [o] { return runEval(*o); }};
}

}  // namespace stocs::tools
