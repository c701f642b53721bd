// `stocs calibrate`: fits the confidence's logistic model (ConfidenceParams) to labelled runs: the
// evidence of each pose (`stocs estimate --per-object`) joined with whether the pose was right
// (`stocs eval --targets-csv`, adds_success). Prints the coefficients for the configuration and
// the code, the in-sample fit, and what each min_confidence would reject.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "commands.h"
#include "report/object_runs.h"
#include "stocs/estimation/stages/pose_confidence.h"
#include "stocs/eval/logistic_regression.h"
#include "stocs/util/error.h"

namespace stocs::tools {
namespace {

struct CalibrateOptions {
  std::vector<std::string> objects;  // per-object CSVs
  std::vector<std::string> targets;  // targets CSVs, one per objects CSV
  double l2 = 1e-3;
  double min_confidence = ConfidenceParams{}.min_confidence;
  bool depth_alone = false;  // the runs' maps came from depth alone: the depth_alone coefficients
};

/// Of a `stocs eval --targets-csv` file, whether each target's pose was right (adds_success).
std::map<Target, int> readCorrectness(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{}: cannot open", file));
  std::string line;
  std::getline(in, line);
  std::map<std::string, size_t> column;
  std::stringstream header(line);
  for (std::string name; std::getline(header, name, ',');) column[name] = column.size();
  for (const char* name : {"scene_id", "im_id", "obj_id", "adds_success"}) {
    if (!column.count(name)) {
      throw InputError(
          fmt::format("{}: no column '{}' (expected `stocs eval --targets-csv`)", file, name));
    }
  }
  std::map<Target, int> correct;
  for (int line_no = 2; std::getline(in, line); ++line_no) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
    try {
      const Target t{std::stoi(cells.at(column["scene_id"])), std::stoi(cells.at(column["im_id"])),
                     std::stoi(cells.at(column["obj_id"]))};
      correct[t] = std::stoi(cells.at(column["adds_success"])) != 0;
    } catch (const std::exception&) {
      throw InputError(fmt::format("{}:{}: malformed row", file, line_no));
    }
  }
  return correct;
}

struct Samples {
  std::vector<ConfidenceEvidence> evidence;
  std::vector<double> written;  // the confidence the run wrote
  std::vector<int> correct;
};

/// Every pose of the runs with its label; a pose without a target row is an error.
Samples joinRuns(const CalibrateOptions& o) {
  Samples s;
  for (size_t i = 0; i < o.objects.size(); ++i) {
    const std::map<Target, int> correct = readCorrectness(o.targets[i]);
    for (const ObjectRun& run : readObjectRuns(o.objects[i])) {
      if (!run.found) continue;
      const auto it = correct.find(run.target);
      if (it == correct.end()) {
        throw InputError(fmt::format("{}: no row for scene {} image {} object {} of {}",
                                     o.targets[i], run.target.scene_id, run.target.im_id,
                                     run.target.obj_id, o.objects[i]));
      }
      s.evidence.push_back(run.evidence);
      s.written.push_back(run.confidence);
      s.correct.push_back(it->second);
    }
  }
  return s;
}

/// The coefficients as configuration and code: ConfidenceParams' own, or its depth_alone model's.
std::string coefficientsText(const LogisticModel& m, bool depth_alone) {
  std::vector<std::pair<std::string, double>> coefficients = {{"intercept", m.intercept}};
  const auto& names = ConfidenceEvidence::names();
  for (size_t k = 0; k < names.size(); ++k) {
    coefficients.emplace_back(names[k], m.weights[static_cast<Eigen::Index>(k)]);
  }
  std::string yaml = "estimation:\n  confidence:\n";
  if (depth_alone) yaml += "    depth_alone:\n";
  std::vector<std::string> literals;
  for (const auto& [name, value] : coefficients) {
    yaml += fmt::format("{}{}: {:.4f}\n", depth_alone ? "      " : "    ", name, value);
    literals.push_back(fmt::format("{:.4f}f", value));
  }
  std::string cpp;
  if (depth_alone) {
    cpp = fmt::format("  ConfidenceModel depth_alone = {{{}}};\n", fmt::join(literals, ", "));
  } else {
    for (size_t k = 0; k < coefficients.size(); ++k) {
      cpp += fmt::format("  float {} = {};\n", coefficients[k].first, literals[k]);
    }
  }
  return "YAML (config):\n" + yaml + "\nC++ (ConfidenceParams):\n" + cpp;
}

/// A table row: the threshold and the shares of right and of wrong poses below it.
std::string rejectionRow(const std::vector<double>& p, const std::vector<int>& correct,
                         double threshold) {
  double right = 0, right_below = 0, wrong = 0, wrong_below = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    (correct[i] ? right : wrong) += 1;
    (correct[i] ? right_below : wrong_below) += p[i] < threshold;
  }
  return fmt::format("| {:.2f} | {:.1f}% | {:.1f}% |\n", threshold,
                     right ? 100 * right_below / right : 0.0,
                     wrong ? 100 * wrong_below / wrong : 0.0);
}

constexpr const char* kRejectionHeader =
    "| min_confidence | right poses rejected | wrong poses rejected |\n|---|---|---|\n";

std::string fitLine(const ProbabilityFit& fit) {
  return fmt::format("log loss {:.4f}, ROC AUC {:.4f}, calibration error (10 bins) {:.4f}",
                     fit.log_loss, fit.roc_auc, fit.calibration_error);
}

int runCalibrate(const CalibrateOptions& o) {
  if (o.objects.size() != o.targets.size()) {
    throw InputError(fmt::format(
        "--objects and --targets come in pairs: got {} per-object files and {} targets files",
        o.objects.size(), o.targets.size()));
  }
  const Samples s = joinRuns(o);
  const int right = static_cast<int>(std::count(s.correct.begin(), s.correct.end(), 1));
  if (right == 0 || right == static_cast<int>(s.correct.size())) {
    throw InputError(fmt::format("{} poses of which {} right: the fit needs right and wrong ones",
                                 s.correct.size(), right));
  }
  Eigen::MatrixXd x(static_cast<Eigen::Index>(s.evidence.size()), ConfidenceEvidence::kCount);
  Eigen::VectorXd y(x.rows());
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    x.row(i) = s.evidence[static_cast<size_t>(i)].terms().transpose();
    y[i] = s.correct[static_cast<size_t>(i)];
  }
  const LogisticModel model = fitLogistic(x, y, o.l2);
  std::vector<double> p;
  for (Eigen::Index i = 0; i < x.rows(); ++i) p.push_back(model.probability(x.row(i).transpose()));
  fmt::print("{} poses, {} right, {} wrong\n\n{}\n", s.correct.size(), right,
             s.correct.size() - right, coefficientsText(model, o.depth_alone));
  fmt::print("In-sample fit: {}\n\n{}", fitLine(probabilityFit(p, s.correct)), kRejectionHeader);
  for (int percent = 5; percent <= 95; percent += 5) {
    fmt::print("{}", rejectionRow(p, s.correct, percent / 100.0));
  }
  // On runs the fit did not see, this is the held-out check of the confidence in use.
  fmt::print("\nThe confidence the runs wrote: {}\n\n{}{}",
             fitLine(probabilityFit(s.written, s.correct)), kRejectionHeader,
             rejectionRow(s.written, s.correct, o.min_confidence));
  return 0;
}

}  // namespace

Command registerCalibrate(CLI::App& app) {
  auto o = std::make_shared<CalibrateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate", "Fit the pose confidence to labelled runs (docs/confidence.md)");
  cmd->add_option("--objects", o->objects,
                  "Per-object CSV of `stocs estimate --min-confidence 0 --per-object`; repeat, "
                  "one per --targets")
      ->required();
  cmd->add_option("--targets", o->targets,
                  "`stocs eval --targets-csv` CSV of the same run, at the same position")
      ->required();
  cmd->add_option("--l2", o->l2, "L2 penalty on the weights (mean log loss + l2/2 |w|^2)")
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option("--min-confidence", o->min_confidence,
                  "Threshold whose rejections of the runs' written confidence are reported")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_flag("--depth-alone", o->depth_alone,
                "The runs had maps from depth alone (`--prob geometric`): print the coefficients "
                "as estimation.confidence.depth_alone");
  return {cmd, [o] { return runCalibrate(*o); }};
}

}  // namespace stocs::tools
