// `stocs bench`: every method on every dataset and probability source, each run a child
// `stocs estimate` process, then the metrics, sweeps and plots of report/bench_report.h.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <algorithm>
#include <map>
#include <set>

#include "cli_options.h"
#include "commands.h"
#include "report/bench_report.h"
#include "report/child_process.h"
#include "report/eval_report.h"
#include "report/line_plot.h"
#include "report/object_runs.h"
#include "report/progress.h"
#include "stocs/io/bop_results.h"
#include "stocs/io/pcd_scene_dataset.h"
#include "stocs/methods/pose_method.h"
#include "stocs/sim/probability_source.h"
#include "stocs/util/error.h"

namespace stocs::tools {
namespace fs = std::filesystem;
namespace {

struct BenchOptions {
  std::vector<std::string> datasets;
  std::vector<std::string> sources = {"real"};
  std::vector<std::string> methods;
  std::vector<std::string> sweep_methods;
  std::string out;
  std::string split = "test";
  std::vector<int> scenes;
  std::vector<int> objects;
  std::string boundaries = "auto";
  MethodOptions method_options;
  std::vector<double> thresholds = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9};
  std::vector<double> budgets = {0.05, 0.1, 0.2, 0.5, 1.0};
  std::vector<int> base_counts = {5, 10, 20, 50, 100};
  bool no_threshold_sweep = false;
  bool no_budget_sweep = false;
  bool no_bases_sweep = false;
  int budget_bases = 100000;
  double run_timeout = 0;
  bool no_plots = false;
  bool cold = false;
  int repeats = 1;
  PipelineParams params;
  ModelOptions model;
  /// The estimation options of the command line, passed on to every `stocs estimate`.
  std::vector<const CLI::Option*> forwarded;
  std::string command;
};

/// A BOP folder for `dir`: itself, or a conversion under `out` for a PCD scene folder.
fs::path bopFolder(const fs::path& dir, const fs::path& out) {
  if (!isPcdSceneFolder(dir)) return dir;
  const fs::path converted = out / "datasets" / datasetName(dir);
  fs::remove_all(converted);
  const int pixels = convertPcdSceneToBop(dir, converted);
  fmt::print(stderr, "bench: {} converted to a BOP dataset in {} ({} model pixels)\n", dir.string(),
             converted.string(), pixels);
  return converted;
}

std::vector<BenchInput> benchInputs(const BenchOptions& o, std::vector<std::string>& notes) {
  std::vector<BenchInput> inputs;
  for (const std::string& d : o.datasets) {
    const fs::path folder = bopFolder(d, o.out);
    const BopDataset dataset(folder, o.split);
    const std::string name = datasetName(d);
    for (const std::string& spec : o.sources) {
      const auto source = makeProbabilitySource(spec, dataset, o.params.stocs.seed);
      BenchInput input{name, spec, folder, listTargets(dataset, o.scenes, o.objects, source.get())};
      if (input.targets.empty()) {
        notes.push_back(fmt::format("{}: no target has a probability map from source '{}'; skipped",
                                    input.name(), spec));
      } else {
        inputs.push_back(input);
      }
    }
  }
  if (inputs.empty()) {
    throw InputError("no dataset has a target with a probability map from the given sources");
  }
  return inputs;
}

std::vector<BenchRun> plannedRuns(const BenchOptions& o, const BenchData& d) {
  std::vector<BenchRun> runs;
  const auto add = [&](Sweep sweep, double value, const std::string& stem) {
    for (size_t i = 0; i < d.inputs.size(); ++i) {
      for (const std::string& method : sweep == Sweep::kNone ? d.methods : d.swept_methods) {
        BenchRun r;
        r.input = i;
        r.method = method;
        r.sweep = sweep;
        r.value = value;
        const fs::path dir = fs::path(o.out) / "runs" / d.inputs[i].tag() / method;
        r.results = sweep == Sweep::kNone
                        ? fs::path(o.out) / "bop" / d.inputs[i].tag() / (method + ".csv")
                        : dir / (stem + ".csv");
        r.per_object = dir / (stem + ".objects.csv");
        r.log = dir / (stem + ".log");
        runs.push_back(r);
      }
    }
  };
  add(Sweep::kNone, 0, "main");
  for (double t : d.thresholds) add(Sweep::kThreshold, t, fmt::format("threshold-{:g}", t));
  for (double b : d.budgets) add(Sweep::kBudget, b, fmt::format("budget-{:g}", b));
  for (double n : d.base_counts) add(Sweep::kBases, n, fmt::format("bases-{:g}", n));
  return runs;
}

std::string joined(const std::vector<int>& ids) {
  return fmt::format("{}", fmt::join(ids, ","));
}

std::vector<std::string> childCommand(const BenchOptions& o, const BenchInput& input,
                                      const BenchRun& r) {
  std::map<std::string, std::vector<std::string>> set_here = {
      {"--hard-threshold", {fmt::format("{}", o.method_options.hard_threshold)}}};
  if (r.sweep == Sweep::kThreshold) {
    set_here["--epsilon"] = set_here["--hard-threshold"] = {fmt::format("{}", r.value)};
  } else if (r.sweep == Sweep::kBudget) {
    set_here["--time-budget"] = {fmt::format("{}", r.value)};
    set_here["--bases"] = {std::to_string(o.budget_bases)};
  } else if (r.sweep == Sweep::kBases) {
    set_here["--bases"] = {fmt::format("{:g}", r.value)};
  }
  std::vector<std::string> argv = {selfExecutable().string(),
                                   "estimate",
                                   "--dataset",
                                   input.dataset.string(),
                                   "--split",
                                   o.split,
                                   "--prob",
                                   input.source,
                                   "--method",
                                   r.method,
                                   "--boundaries",
                                   o.boundaries,
                                   "--out",
                                   r.results.string(),
                                   "--per-object",
                                   r.per_object.string()};
  if (!o.cold) argv.push_back("--warm-up");
  if (o.repeats > 1) argv.insert(argv.end(), {"--repeats", std::to_string(o.repeats)});
  if (!o.scenes.empty()) argv.insert(argv.end(), {"--scenes", joined(o.scenes)});
  if (!o.objects.empty()) argv.insert(argv.end(), {"--objects", joined(o.objects)});
  for (const CLI::Option* opt : o.forwarded) {
    const std::string name = opt->get_name();
    if (opt->count() == 0 || set_here.count(name)) continue;
    argv.push_back(name);
    if (opt->get_expected_max() > 0)
      argv.insert(argv.end(), opt->results().begin(), opt->results().end());
  }
  for (const auto& [name, values] : set_here) {
    argv.push_back(name);
    argv.insert(argv.end(), values.begin(), values.end());
  }
  return argv;
}

/// Runs one child and scores what it wrote; a crash or unusable output leaves every target missing.
void execute(const BenchOptions& o, const BenchData& d, DatasetEvaluator& evaluator, BenchRun& r,
             Progress& progress) {
  const BenchInput& input = d.inputs[r.input];
  for (const fs::path& f : {r.results, r.per_object, r.log}) {
    fs::create_directories(f.parent_path());
    std::error_code ignored;  // a leftover that cannot be removed makes the run fail, not the bench
    fs::remove(f, ignored);
  }
  r.child = runChild(
      childCommand(o, input, r), r.log, [&] { progress.update(); }, o.run_timeout);
  std::vector<BopResult> results;
  std::map<Target, ObjectRun> timings;
  if (!r.child.ok()) {
    r.failure = fmt::format("{}, see {}", r.child.describe(), r.log.string());
  } else {
    try {
      results = readBopResults(r.results);
      for (const ObjectRun& run : readObjectRuns(r.per_object)) timings[run.target] = run;
    } catch (const InputError& e) {
      r.failure = fmt::format("unusable output: {}", e.what());
      results.clear();
      timings.clear();
    }
  }
  r.targets = evaluator.evaluate(input.targets, results, r.results.string()).targets;
  constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
  for (const TargetResult& t : r.targets) {
    const auto it = timings.find(t.target);
    r.seconds.push_back(it == timings.end() ? kUnknown : it->second.seconds);
    r.cpu_seconds.push_back(it == timings.end() ? kUnknown : it->second.cpu_seconds);
  }
  progress.finish(r.failure.empty() ? "ok" : "FAILED: " + r.failure);
}

/// The options given, for the report: lists as typed (`--methods a,b`), others once per value.
std::string commandLine(const CLI::App& cmd) {
  std::string line = "stocs " + cmd.get_name();
  for (const CLI::Option* opt : cmd.get_options()) {
    if (opt->count() == 0) continue;
    if (opt->get_expected_max() == 0) {
      line += " " + opt->get_name();
    } else if (opt->get_delimiter() != '\0') {
      const std::string delimiter(1, opt->get_delimiter());
      line += fmt::format(" {} {}", opt->get_name(), fmt::join(opt->results(), delimiter));
    } else {
      for (const std::string& v : opt->results()) line += " " + opt->get_name() + " " + v;
    }
  }
  return line;
}

void validate(const BenchOptions& o) {
  validatePipelineOptions(o.params);
  for (const std::string& m : o.methods) makeMethod(m, o.method_options);
  for (const std::string& m : o.sweep_methods) {
    if (std::find(o.methods.begin(), o.methods.end(), m) == o.methods.end())
      throw InputError(fmt::format("sweep method '{}' is not one of the methods run", m));
  }
  for (double t : o.thresholds) {
    if (!(t > 0 && t < 1)) throw InputError(fmt::format("threshold {} is outside (0, 1)", t));
  }
  for (double b : o.budgets) {
    if (!(b > 0 && b <= 3600))
      throw InputError(fmt::format("time budget {} s is outside (0, 3600]", b));
  }
  if (!(o.run_timeout >= 0)) throw InputError("run timeout must not be negative");
  for (int n : o.base_counts) {
    if (n < 1 || n > 1000000)
      throw InputError(fmt::format("base count {} is outside [1, 1000000]", n));
  }
  if (o.budget_bases < 1 || o.budget_bases > 1000000) {
    throw InputError(fmt::format("budget bases {} is outside [1, 1000000]", o.budget_bases));
  }
  if (!o.no_plots && findGnuplot().empty()) {
    throw InputError(
        "plots need gnuplot (Debian package gnuplot-nox; scripts/install_deps.sh "
        "installs it), or pass --no-plots");
  }
}

int runBench(BenchOptions o) {
  if (o.methods.empty()) o.methods = methodNames();
  validate(o);
  fs::create_directories(o.out);
  BenchData d;
  d.command = o.command;
  d.warm = !o.cold;
  d.repeats = o.repeats;
  d.methods = o.methods;
  d.swept_methods = o.sweep_methods.empty() ? o.methods : o.sweep_methods;
  if (!o.no_threshold_sweep) d.thresholds = o.thresholds;
  if (!o.no_budget_sweep) d.budgets = o.budgets;
  if (!o.no_bases_sweep) {
    std::set<int> counts(o.base_counts.begin(), o.base_counts.end());
    d.base_counts.assign(counts.begin(), counts.end());
  }
  d.inputs = benchInputs(o, d.notes);
  d.runs = plannedRuns(o, d);

  std::vector<std::unique_ptr<BopDataset>> datasets;
  std::vector<std::unique_ptr<DatasetEvaluator>> evaluators;
  for (const BenchInput& input : d.inputs) {
    datasets.push_back(std::make_unique<BopDataset>(input.dataset, o.split));
    evaluators.push_back(std::make_unique<DatasetEvaluator>(*datasets.back()));
  }
  Progress progress(d.runs.size(), isatty(STDERR_FILENO));
  for (BenchRun& r : d.runs) {
    progress.start(r.label(d.inputs));
    execute(o, d, *evaluators[r.input], r, progress);
  }
  progress.close();
  writeBenchReport(d, o.out, !o.no_plots);
  fmt::print(stderr, "bench: report in {}\n", (fs::path(o.out) / "results.md").string());
  return 0;
}

}  // namespace

Command registerBench(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand(
      "bench", "Run methods side by side on datasets and probability sources; tables and plots");
  cmd->add_option("--dataset", o->datasets,
                  "BOP dataset folder, or a PCD scene folder with gt.json (converted); repeatable")
      ->required();
  cmd->add_option("--out", o->out, "Output folder (report, CSV, BOP results, plots, logs)")
      ->required();
  cmd->add_option("--prob", o->sources,
                  "Probability sources, as `stocs estimate --prob`; repeatable");
  cmd->add_option("--methods", o->methods,
                  "Methods, comma-separated (default: all: " +
                      fmt::format("{}", fmt::join(methodNames(), ", ")) + ")")
      ->delimiter(',');
  cmd->add_option("--sweep-methods", o->sweep_methods,
                  "Methods run again in the sweeps, comma-separated (default: every method run)")
      ->delimiter(',');
  addSelectionOptions(*cmd, o->split, o->scenes, o->objects);
  cmd->add_option("--boundaries", o->boundaries,
                  "Instance boundaries: 'auto' (edge/ maps, else from rgb/ when searching several "
                  "instances) or 'off'")
      ->check(CLI::IsMember({"auto", "off"}));
  cmd->add_option("--hard-threshold", o->method_options.hard_threshold,
                  "Hard-segment threshold of the main runs");
  cmd->add_option("--thresholds", o->thresholds, "Segmentation thresholds of the sweep")
      ->delimiter(',');
  cmd->add_flag("--no-threshold-sweep", o->no_threshold_sweep, "Skip the threshold sweep");
  cmd->add_option("--budgets", o->budgets, "Time budgets (s per object) of the anytime sweep")
      ->delimiter(',');
  cmd->add_flag("--no-budget-sweep", o->no_budget_sweep, "Skip the time-budget sweep");
  cmd->add_option("--budget-bases", o->budget_bases,
                  "Bases in the budget sweep, so many that the budget ends the search");
  cmd->add_option("--base-counts", o->base_counts,
                  "Bases per object of the base-count sweep (speed against accuracy; the 4PCS "
                  "methods' iterations)")
      ->delimiter(',');
  cmd->add_flag("--no-bases-sweep", o->no_bases_sweep, "Skip the base-count sweep");
  cmd->add_option("--run-timeout", o->run_timeout,
                  "Seconds after which a run is killed and counted as failed (0: no limit)");
  cmd->add_flag("--no-plots", o->no_plots, "Write no PNG plots (no gnuplot needed)");
  cmd->add_flag("--cold", o->cold,
                "Time every run's first object cold: without `stocs estimate --warm-up`, its time "
                "includes the process's first-call costs (thread pools, first-touch memory)");
  cmd->add_option("--repeats", o->repeats,
                  "Process every image this many times in a row (`stocs estimate --repeats`): "
                  "times are medians over the repeats")
      ->check(CLI::Range(1, 1000));
  const size_t before = cmd->get_options().size();
  addModelOptions(*cmd, o->model);
  addPipelineOptions(*cmd, o->params);
  for (size_t i = before; i < cmd->get_options().size(); ++i) {
    o->forwarded.push_back(cmd->get_options()[i]);
  }
  return {cmd, [o, cmd] {
            o->command = commandLine(*cmd);
            return runBench(*o);
          }};
}

}  // namespace stocs::tools
