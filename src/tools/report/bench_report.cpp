#include "bench_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <fstream>
#include <optional>
#include <thread>

#include "confidence_report.h"
#include "eval_report.h"
#include "line_plot.h"
#include "stocs/eval/accuracy_curve.h"

namespace stocs::tools {
namespace {

using Scope = std::optional<size_t>;  ///< one input, or every input pooled

/// The targets and timings of the runs of one method at one setting, over a scope.
struct Pool {
  std::vector<TargetErrors> errors;  ///< of the targets whose object is present
  std::vector<ScoredTarget> scored;  ///< every target, for the confidence metrics
  std::vector<double> seconds;       ///< where known
  std::vector<double> cpu_seconds;   ///< where known
  double peak_mb = 0;
  int failed_runs = 0;
};

Pool pool(const BenchData& d, const std::string& method, Sweep sweep, double value, Scope scope) {
  Pool p;
  for (const BenchRun& r : d.runs) {
    if (r.method != method || r.sweep != sweep || (sweep != Sweep::kNone && r.value != value) ||
        (scope && r.input != *scope)) {
      continue;
    }
    const std::vector<ScoredTarget> scored = scoredTargets(r.targets);
    p.scored.insert(p.scored.end(), scored.begin(), scored.end());
    for (size_t i = 0; i < r.targets.size(); ++i) {
      if (!r.targets[i].absent()) p.errors.push_back(r.targets[i].errors);
      if (!std::isnan(r.seconds[i])) p.seconds.push_back(r.seconds[i]);
      if (!std::isnan(r.cpu_seconds[i])) p.cpu_seconds.push_back(r.cpu_seconds[i]);
    }
    p.peak_mb = std::max(p.peak_mb, r.child.peak_rss_mb);
    p.failed_runs += !r.failure.empty();
  }
  return p;
}

/// Each input, then all of them pooled when there are several.
std::vector<Scope> scopes(const BenchData& d) {
  std::vector<Scope> s;
  for (size_t i = 0; i < d.inputs.size(); ++i) s.push_back(i);
  if (d.inputs.size() > 1) s.push_back(std::nullopt);
  return s;
}

/// The widest scope: all inputs pooled, or the only one.
Scope widest(const BenchData& d) {
  return d.inputs.size() == 1 ? Scope(0) : std::nullopt;
}

std::vector<Cell> scopeCells(const BenchData& d, Scope scope) {
  if (!scope) return {textCell("all"), textCell("all")};
  return {textCell(d.inputs[*scope].dataset_name), textCell(d.inputs[*scope].source)};
}

std::string scopeName(const BenchData& d, Scope scope) {
  return scope ? d.inputs[*scope].name() : "all datasets";
}

std::string scopeTag(const BenchData& d, Scope scope) {
  return scope ? d.inputs[*scope].tag() : "all";
}

std::vector<Cell> withMetrics(std::vector<Cell> head) {
  for (const Cell& c : metricHeader()) head.push_back(c);
  return head;
}

ReportTable mainTable(const BenchData& d) {
  std::vector<Cell> header =
      withMetrics({textCell("method"), textCell("dataset"), textCell("source")});
  for (Cell c : std::vector<Cell>{{"time median (s)", "time_median_s"},
                                  {"time p90 (s)", "time_p90_s"},
                                  {"CPU median (s)", "cpu_median_s"},
                                  {"CPU p90 (s)", "cpu_p90_s"},
                                  {"peak memory (MB)", "peak_memory_mb"},
                                  {"failed runs", "failed_runs"}}) {
    header.push_back(c);
  }
  for (const Cell& c : confidenceHeader()) header.push_back(c);
  ReportTable table(header);
  for (const std::string& method : d.methods) {
    for (Scope scope : scopes(d)) {
      const Pool p = pool(d, method, Sweep::kNone, 0, scope);
      std::vector<Cell> row = {textCell(method)};
      for (const Cell& c : scopeCells(d, scope)) row.push_back(c);
      for (const Cell& c : metricCells(summarize(p.errors))) row.push_back(c);
      row.push_back(numberCell(quantile(p.seconds, 0.5), 3));
      row.push_back(numberCell(quantile(p.seconds, 0.9), 3));
      row.push_back(numberCell(quantile(p.cpu_seconds, 0.5), 3));
      row.push_back(numberCell(quantile(p.cpu_seconds, 0.9), 3));
      row.push_back(numberCell(p.peak_mb, 0));
      row.push_back(textCell(std::to_string(p.failed_runs)));
      for (const Cell& c : confidenceCells(confidenceMetrics(p.scored, d.min_confidence))) {
        row.push_back(c);
      }
      table.add(row);
    }
  }
  return table;
}

Cell sweepValueHeader(Sweep sweep) {
  switch (sweep) {
    case Sweep::kThreshold:
      return {"segmentation threshold", "threshold"};
    case Sweep::kBudget:
      return {"time budget (s)", "time_budget_s"};
    default:
      return {"bases", "bases"};
  }
}

/// Sweep results at every value; `only` restricts the rows to one scope (markdown), else all.
ReportTable sweepTable(const BenchData& d, Sweep sweep, const std::vector<double>& values,
                       std::optional<Scope> only) {
  std::vector<Cell> header = withMetrics(
      {textCell("method"), textCell("dataset"), textCell("source"), sweepValueHeader(sweep)});
  header.push_back({"time median (s)", "time_median_s"});
  header.push_back({"CPU median (s)", "cpu_median_s"});
  ReportTable table(header);
  for (const std::string& method : d.swept_methods) {
    for (Scope scope : scopes(d)) {
      if (only && scope != *only) continue;
      for (double v : values) {
        const Pool p = pool(d, method, sweep, v, scope);
        std::vector<Cell> row = {textCell(method)};
        for (const Cell& c : scopeCells(d, scope)) row.push_back(c);
        row.push_back(textCell(fmt::format("{:g}", v)));
        for (const Cell& c : metricCells(summarize(p.errors))) row.push_back(c);
        row.push_back(numberCell(quantile(p.seconds, 0.5), 3));
        row.push_back(numberCell(quantile(p.cpu_seconds, 0.5), 3));
        table.add(row);
      }
    }
  }
  return table;
}

/// A plot of percentages, with room above 100% so that lines there stay visible.
LinePlot percentPlot(const std::string& title, const std::string& x_label,
                     const std::string& y_label) {
  LinePlot plot;
  plot.title = title;
  plot.x_label = x_label;
  plot.y_label = y_label;
  plot.y_min = 0;
  plot.y_max = 105;
  return plot;
}

LinePlot accuracyPlot(const BenchData& d, Scope scope) {
  LinePlot plot = percentPlot("ADD-S accuracy-threshold curve, " + scopeName(d, scope),
                              "ADD-S threshold (cm)", "accuracy (%)");
  plot.x_min = 0;
  plot.x_max = kAddsCurveLimitMm / 10;
  plot.markers = false;
  for (const std::string& method : d.methods) {
    std::vector<double> adds;
    for (const TargetErrors& e : pool(d, method, Sweep::kNone, 0, scope).errors) {
      adds.push_back(e.adds_mm);
    }
    PlotSeries s{
        fmt::format("{} (AUC {:.1f}%)", method, 100 * accuracyCurveArea(adds, kAddsCurveLimitMm)),
        {}};
    for (int i = 0; i <= 400; ++i) {
      const double x_mm = kAddsCurveLimitMm * i / 400;
      s.points.emplace_back(x_mm / 10, 100 * accuracyBelow(adds, x_mm));
    }
    if (!adds.empty()) plot.series.push_back(s);
  }
  return plot;
}

/// Each method's reliability diagram (share correct against mean score per score bin).
LinePlot scoreReliabilityPlot(const BenchData& d, Scope scope) {
  std::vector<std::pair<std::string, ConfidenceMetrics>> series;
  for (const std::string& method : d.methods) {
    series.emplace_back(method, confidenceMetrics(pool(d, method, Sweep::kNone, 0, scope).scored,
                                                  d.min_confidence));
  }
  return reliabilityPlot("Score reliability, " + scopeName(d, scope), series);
}

LinePlot thresholdPlot(const BenchData& d, Scope scope) {
  LinePlot plot =
      percentPlot("Success rate vs segmentation threshold, " + scopeName(d, scope),
                  "segmentation threshold (StoCS: epsilon; hard-segment methods: threshold)",
                  "success: error < 2 cm and 10° (%)");
  plot.x_min = 0;
  plot.x_max = 1;
  for (const std::string& method : d.swept_methods) {
    PlotSeries s{method, {}};
    for (double t : d.thresholds) {
      const Pool p = pool(d, method, Sweep::kThreshold, t, scope);
      if (!p.errors.empty()) s.points.emplace_back(t, 100 * summarize(p.errors).rt_success);
    }
    plot.series.push_back(s);
  }
  return plot;
}

/// ADD-S AUC against median time per object, one point per value of a sweep.
LinePlot timeAccuracyPlot(const BenchData& d, Scope scope, Sweep sweep,
                          const std::vector<double>& values, const std::string& title,
                          const std::string& point) {
  LinePlot plot =
      percentPlot(title + ", " + scopeName(d, scope),
                  "median time per object (s), one point per " + point, "ADD-S AUC (%)");
  plot.log_x = true;
  for (const std::string& method : d.swept_methods) {
    PlotSeries s{method, {}};
    for (double v : values) {
      const Pool p = pool(d, method, sweep, v, scope);
      const double time = quantile(p.seconds, 0.5);
      if (time > 0) s.points.emplace_back(time, 100 * summarize(p.errors).adds_auc);
    }
    plot.series.push_back(s);
  }
  return plot;
}

LinePlot anytimePlot(const BenchData& d, Scope scope) {
  return timeAccuracyPlot(d, scope, Sweep::kBudget, d.budgets, "Accuracy vs time budget (anytime)",
                          "budget");
}

LinePlot basesPlot(const BenchData& d, Scope scope) {
  return timeAccuracyPlot(d, scope, Sweep::kBases, d.base_counts, "Accuracy vs bases",
                          "base count");
}

/// Issue 6's comparison: each swept method at its fewest bases from which on its ADD-S AUC is at
/// least that of another method's main run (at that count and every larger one swept, so that one
/// lucky low count does not decide), over the widest scope, with the time ratios (other / swept).
ReportTable equalAccuracyTable(const BenchData& d) {
  ReportTable table({textCell("method"),
                     textCell("against"),
                     {"its ADD-S AUC", "against_adds_auc"},
                     {"its time median (s)", "against_time_median_s"},
                     {"its CPU median (s)", "against_cpu_median_s"},
                     {"fewest bases at equal or better AUC from there on", "bases"},
                     {"ADD-S AUC", "adds_auc"},
                     {"time median (s)", "time_median_s"},
                     {"CPU median (s)", "cpu_median_s"},
                     {"faster by (time)", "time_ratio"},
                     {"faster by (CPU)", "cpu_ratio"}});
  const Scope scope = widest(d);
  const auto median = [](const std::vector<double>& v) { return quantile(v, 0.5); };
  for (const std::string& method : d.swept_methods) {
    // The method's sweep, pooled once for every method it is compared with.
    std::vector<Pool> swept;
    std::vector<double> aucs;
    for (double n : d.base_counts) {
      swept.push_back(pool(d, method, Sweep::kBases, n, scope));
      aucs.push_back(summarize(swept.back().errors).adds_auc);
    }
    for (const std::string& against : d.methods) {
      if (against == method) continue;
      const Pool other = pool(d, against, Sweep::kNone, 0, scope);
      const double target_auc = summarize(other.errors).adds_auc;
      std::vector<Cell> row = {textCell(method), textCell(against), percentCell(target_auc),
                               numberCell(median(other.seconds), 3),
                               numberCell(median(other.cpu_seconds), 3)};
      const size_t k = firstIndexReachingFromThereOn(aucs, target_auc);
      if (k == aucs.size()) {
        row.push_back(textCell("none"));
        for (int i = 0; i < 5; ++i) row.push_back(numberCell(std::nan(""), 0));
      } else {
        const Pool& p = swept[k];
        row.push_back(textCell(fmt::format("{:g}", d.base_counts[k])));
        row.push_back(percentCell(aucs[k]));
        row.push_back(numberCell(median(p.seconds), 3));
        row.push_back(numberCell(median(p.cpu_seconds), 3));
        row.push_back(numberCell(median(other.seconds) / median(p.seconds), 1));
        row.push_back(numberCell(median(other.cpu_seconds) / median(p.cpu_seconds), 1));
      }
      table.add(row);
    }
  }
  return table;
}

std::string machine() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string model = "unknown CPU";
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  }
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", &utc);
  // Wall times depend on what else ran: the load when the report is written covers the run's end.
  std::ifstream loadavg("/proc/loadavg");
  double load[3] = {NAN, NAN, NAN};
  loadavg >> load[0] >> load[1] >> load[2];
  return fmt::format(
      "{} cores of {}; {}; load average at the end (1, 5, 15 min) {:.2f}, {:.2f}, {:.2f}",
      std::thread::hardware_concurrency(), model, date, load[0], load[1], load[2]);
}

std::vector<LabelledTarget> mainTargets(const BenchData& d) {
  std::vector<LabelledTarget> rows;
  for (const BenchRun& r : d.runs) {
    if (r.sweep != Sweep::kNone) continue;
    for (size_t i = 0; i < r.targets.size(); ++i) {
      rows.push_back({{r.method, d.inputs[r.input].dataset_name, d.inputs[r.input].source},
                      r.targets[i],
                      r.seconds[i]});
    }
  }
  return rows;
}

/// A plot of one scope of a bench.
using MakePlot = LinePlot (*)(const BenchData&, Scope);

/// A sweep's section of the report.
struct SweepSection {
  Sweep sweep;
  const std::vector<double>& values;
  const char* heading;
  const char* how;
  const char* stem;  ///< of its figures and CSV file
  MakePlot plot;
};

/// Writes a bench's report section by section: results.md, the CSV files beside it and, when
/// asked, the figures in plots/.
class BenchReportWriter {
 public:
  BenchReportWriter(const BenchData& d, const std::filesystem::path& out, bool plots)
      : d_(d), out_(out), plots_(plots) {
    // The pooled figure first, then one per input when there are several.
    plot_scopes_ = {widest(d)};
    if (d.inputs.size() > 1) {
      for (size_t i = 0; i < d.inputs.size(); ++i) plot_scopes_.push_back(i);
    }
  }

  /// Writes every file of the report.
  void write() const {
    std::string md = methodsSection();
    md += "\n## ADD-S accuracy-threshold curves\n" + figures("accuracy_threshold", accuracyPlot);
    md += "\n## Score reliability\n" + figures("reliability", scoreReliabilityPlot);
    md += sweepSections() + equalAccuracySection() + notesSection();
    writeTextFile(out_ / "results.md", md);
  }

 private:
  /// The title, the command, the machine and the table of methods x datasets (also written to
  /// summary.csv, its targets to targets.csv).
  std::string methodsSection() const {
    const ReportTable main_table = mainTable(d_);
    std::string md =
        fmt::format("# stocs bench\n\n```\n{}\n```\n\nMachine: {}.\n\n", d_.command, machine());
    md += "## Methods x datasets\n\n" + main_table.markdown() + "\n" + metricLegend() +
          timeLegend() + "\n" + confidenceLegend(d_.min_confidence);
    writeTextFile(out_ / "summary.csv", main_table.csv());
    writeTextFile(out_ / "targets.csv",
                  targetsCsv({"method", "dataset", "source"}, mainTargets(d_)));
    return md;
  }

  /// What the table's time, CPU, memory and failure columns measure.
  std::string timeLegend() const {
    return "Time per object: the method's wall time for one object (after the frame's images and "
           "the models are loaded), median and 90th percentile over the targets the run reported" +
           std::string(d_.warm ? "; every run first estimated its first object once, untimed "
                                 "(`stocs estimate --warm-up`), so that no target pays for the "
                                 "process's first calls (thread pools, first-touch memory)"
                               : "; cold (`--cold`): the first target of every run includes the "
                                 "process's first-call costs") +
           (d_.repeats > 1 ? fmt::format("; every image was processed {} times in a row and a "
                                         "target's time is the median over them (`--repeats`)",
                                         d_.repeats)
                           : std::string()) +
           ". CPU: the CPU time of the process, all its threads, during the same call; on a shared "
           "machine it is not inflated by other processes as wall time is. Peak memory: the "
           "maximum resident set size of the `stocs estimate` process that ran the "
           "method on the dataset (one process per run). Failed runs: runs that crashed or exited "
           "with an error; their targets count as missing.\n";
  }

  /// The figures `make` draws for every plot scope, rendered when plots are asked for; their
  /// markdown links, or nothing without plots.
  std::string figures(const std::string& stem, MakePlot make) const {
    std::string links;
    for (Scope scope : plot_scopes_) {
      const std::string file = fmt::format("plots/{}_{}.png", stem, scopeTag(d_, scope));
      if (plots_) renderPlot(make(d_, scope), out_ / file);
      links += fmt::format("![{}, {}]({})\n", stem, scopeName(d_, scope), file);
    }
    return plots_ ? "\n" + links : std::string();
  }

  /// A section per sweep that ran: its table and figures (each also written to <stem>.csv).
  std::string sweepSections() const {
    const SweepSection sections[] = {
        {Sweep::kThreshold, d_.thresholds, "Success rate versus segmentation threshold",
         "Each method run again at every threshold: StoCS's epsilon (`--epsilon`) and the hard "
         "segment's threshold (`--hard-threshold`) are both set to it.",
         "threshold_sweep", thresholdPlot},
        {Sweep::kBudget, d_.budgets, "Accuracy versus time budget (anytime)",
         "Each method run again with `--time-budget` at every value, with a number of bases so "
         "large that the budget ends the search.",
         "budget_sweep", anytimePlot},
        {Sweep::kBases, d_.base_counts, "Accuracy versus bases",
         "Each method run again with `--bases` at every value (PCL's 4PCS: its iterations; "
         "OpenCV's PPF has no such setting, so its rows only repeat).",
         "bases_sweep", basesPlot},
    };
    std::string md;
    for (const SweepSection& s : sections) {
      if (s.values.empty()) continue;
      md += fmt::format("\n## {}\n\n{}\n\n", s.heading, s.how) +
            sweepTable(d_, s.sweep, s.values, widest(d_)).markdown() + figures(s.stem, s.plot);
      writeTextFile(out_ / (std::string(s.stem) + ".csv"),
                    sweepTable(d_, s.sweep, s.values, std::nullopt).csv());
    }
    return md;
  }

  /// Speed at equal or better accuracy, when bases were swept and there is another method to
  /// compare with (also written to equal_accuracy.csv); nothing otherwise.
  std::string equalAccuracySection() const {
    if (d_.base_counts.empty() || d_.methods.size() <= 1) return {};
    const ReportTable table = equalAccuracyTable(d_);
    writeTextFile(out_ / "equal_accuracy.csv", table.csv());
    return "\n## Speed at equal or better accuracy\n\nEach method of the base-count sweep at "
           "the fewest bases from which on (at that count and every larger one swept) its ADD-S "
           "AUC, over " +
           scopeName(d_, widest(d_)) +
           ", is at least that of another method's main run; \"faster by\" is the other "
           "method's median time per object over this one's (above 1: this method is faster). "
           "\"none\": not even the largest swept count reached that AUC.\n\n" +
           table.markdown();
  }

  /// The bench's notes and the runs that failed, or nothing when there are none.
  std::string notesSection() const {
    std::string notes;
    for (const std::string& n : d_.notes) notes += "- " + n + "\n";
    for (const BenchRun& r : d_.runs) {
      if (!r.failure.empty()) notes += fmt::format("- {}: {}\n", r.label(d_.inputs), r.failure);
    }
    return notes.empty() ? std::string() : "\n## Notes and failures\n\n" + notes;
  }

  const BenchData& d_;
  const std::filesystem::path& out_;
  bool plots_;
  std::vector<Scope> plot_scopes_;
};

}  // namespace

std::string BenchInput::tag() const {
  std::string t = name();
  std::replace_if(
      t.begin(), t.end(), [](char c) { return !std::isalnum(c) && c != '-' && c != '.'; }, '_');
  return t;
}

std::string BenchRun::label(const std::vector<BenchInput>& inputs) const {
  const std::string base = method + " on " + inputs[input].name();
  if (sweep == Sweep::kThreshold) return fmt::format("{}, threshold {:g}", base, value);
  if (sweep == Sweep::kBudget) return fmt::format("{}, budget {:g} s", base, value);
  if (sweep == Sweep::kBases) return fmt::format("{}, {:g} bases", base, value);
  return base;
}

void writeBenchReport(const BenchData& d, const std::filesystem::path& out, bool plots) {
  BenchReportWriter(d, out, plots).write();
}

}  // namespace stocs::tools
