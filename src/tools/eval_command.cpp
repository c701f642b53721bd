// `stocs eval`: the metrics of BOP results files against their datasets' ground truth, per object,
// per dataset and overall, as markdown and CSV.
#include <fmt/format.h>

#include <iostream>
#include <map>

#include "cli_options.h"
#include "commands.h"
#include "coverage_report.h"
#include "eval_report.h"
#include "stocs/eval/dataset_evaluation.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/sim/probability_source.h"
#include "stocs/util/error.h"

namespace stocs::tools {
namespace {

struct EvalOptions {
  std::vector<std::string> datasets;
  std::vector<std::string> results;
  std::string split = "test";
  std::vector<int> scenes;
  std::vector<int> objects;
  std::string prob;
  std::string markdown;
  std::string csv;
  std::string targets_csv;
  std::vector<std::string> per_object;
};

int runEval(const EvalOptions& o) {
  if (o.datasets.size() != o.results.size()) {
    throw InputError(
        fmt::format("--dataset and --results come in pairs: got {} datasets and {} "
                    "results files",
                    o.datasets.size(), o.results.size()));
  }
  if (!o.per_object.empty() && o.per_object.size() != o.results.size()) {
    throw InputError(fmt::format("--per-object and --results come in pairs: got {} and {}",
                                 o.per_object.size(), o.results.size()));
  }
  std::vector<Cell> header = {textCell("results"), textCell("dataset"), textCell("object")};
  for (const Cell& c : metricHeader()) header.push_back(c);
  ReportTable table(header);
  const auto add_row = [&](const std::string& results, const std::string& dataset,
                           const std::string& object, const std::vector<TargetResult>& targets) {
    std::vector<Cell> row = {textCell(results), textCell(dataset), textCell(object)};
    for (const Cell& c : metricCells(summarize(errorsOf(targets)))) row.push_back(c);
    table.add(row);
  };
  std::vector<LabelledTarget> rows;
  std::vector<TargetResult> everything;
  std::string notes;
  for (size_t i = 0; i < o.datasets.size(); ++i) {
    const BopDataset dataset(o.datasets[i], o.split);
    const std::string name = datasetName(dataset.root());
    std::unique_ptr<ProbabilitySource> source;
    if (!o.prob.empty()) source = makeProbabilitySource(o.prob, dataset, 0);
    const std::vector<Target> targets = listTargets(dataset, o.scenes, o.objects, source.get());
    if (targets.empty()) {
      throw InputError(fmt::format(
          "dataset {}: no target among the selected scenes and objects{}", o.datasets[i],
          o.prob.empty() ? "" : " with a map from source '" + o.prob + "'"));
    }
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
      add_row(o.results[i], name, std::to_string(obj), targets_of_obj);
    }
    add_row(o.results[i], name, "all", ev.targets);
    if (!o.per_object.empty())
      notes += coverageNote(o.results[i], o.per_object[i], ev.targets, dataset);
    if (ev.duplicates || ev.not_targets) {
      notes += fmt::format(
          "- {}: {} rows beyond a target's highest-scoring one and {} rows for objects that are "
          "not targets were ignored.\n",
          o.results[i], ev.duplicates, ev.not_targets);
    }
  }
  if (o.datasets.size() > 1) add_row("all", "all", "all", everything);

  const std::string markdown =
      table.markdown() + "\n" + metricLegend() + (notes.empty() ? "" : "\n" + notes);
  if (o.markdown.empty()) {
    std::cout << markdown;
  } else {
    writeTextFile(o.markdown, markdown);
  }
  if (!o.csv.empty()) writeTextFile(o.csv, table.csv());
  if (!o.targets_csv.empty())
    writeTextFile(o.targets_csv, targetsCsv({"results", "dataset"}, rows));
  return 0;
}

}  // namespace

Command registerEval(CLI::App& app) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* cmd = app.add_subcommand(
      "eval", "Pose metrics of BOP results against ground truth (ADD, ADD-S, AUC, APC errors)");
  cmd->add_option("--dataset", o->datasets, "BOP dataset folder; repeat, one per --results")
      ->required();
  cmd->add_option("--results", o->results, "BOP results CSV of the --dataset at the same position")
      ->required();
  addSelectionOptions(*cmd, o->split, o->scenes, o->objects);
  cmd->add_option("--prob", o->prob,
                  "Only targets with a probability map from this source (as `stocs estimate "
                  "--prob`); default: every object of scene_gt.json");
  cmd->add_option("--markdown", o->markdown, "Markdown report file (default: standard output)");
  cmd->add_option("--csv", o->csv, "Summary rows as CSV");
  cmd->add_option("--per-object", o->per_object,
                  "`stocs estimate --per-object` file of each --results: reports the share of true "
                  "errors of correct poses inside the covariances' 50% and 90% ellipsoids");
  cmd->add_option("--targets-csv", o->targets_csv, "One CSV row per target with every error");
  return {cmd, [o] { return runEval(*o); }};
}

}  // namespace stocs::tools
