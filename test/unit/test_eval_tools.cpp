// The evaluation tools end to end: `stocs eval` (known poses give exact metrics; bad inputs exit 2
// naming the problem), `stocs estimate --per-object` (the times the benchmark reads) and a small
// `stocs bench` with StoCS and its hard-segment ablation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>

#include "stocs/io/bop_dataset.h"
#include "stocs/io/bop_results.h"
#include "stocs/io/mesh_io.h"
#include "test_support.h"

namespace stocs {
namespace {

const std::string kTool = STOCS_TOOL_PATH;

double number(const std::map<std::string, std::string>& row, const std::string& column) {
  return std::stod(row.at(column));
}

class EvalCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::scratchDir("eval_cli");
    truth_ = test::writeSyntheticBopDataset(root_ / "data");
  }

  /// Writes a results file holding the truth moved by `shift_mm` (camera frame) and turned by
  /// `turn` (object frame).
  std::string results(const std::string& name, const Eigen::Vector3d& shift_mm,
                      const Eigen::Matrix3d& turn = Eigen::Matrix3d::Identity()) const {
    BopResult r;
    r.obj_id = 1;
    r.score = 1;
    r.R = truth_.linear().cast<double>() * turn;
    r.t_mm = truth_.translation().cast<double>() * 1000 + shift_mm;
    r.time = 0.5;
    writeBopResults(root_ / name, {r});
    return (root_ / name).string();
  }

  std::string data() const { return (root_ / "data").string(); }

  /// `stocs bench` on the generated frame into root_/bench with `options`; its exit code.
  int bench(const std::string& options, std::string& log) const {
    return test::runCommand(kTool + " bench --dataset " + data() + " --out " +
                                (root_ / "bench").string() + " " + options,
                            log);
  }

  std::filesystem::path root_;
  Eigen::Isometry3f truth_;
};

TEST_F(EvalCliTest, KnownPosesGiveExactMetrics) {
  const std::string exact = results("exact.csv", Eigen::Vector3d::Zero());
  const std::string shifted = results("shifted.csv", {3, 4, 0});
  const std::string turned =
      results("turned.csv", Eigen::Vector3d::Zero(),
              Eigen::AngleAxisd(33 * M_PI / 180, Eigen::Vector3d::UnitX()).toRotationMatrix());
  std::string out;
  ASSERT_EQ(
      test::runCommand(kTool + " eval --dataset " + data() + " --results " + exact + " --dataset " +
                           data() + " --results " + shifted + " --dataset " + data() +
                           " --results " + turned + " --csv " + (root_ / "summary.csv").string() +
                           " --targets-csv " + (root_ / "targets.csv").string(),
                       out),
      0)
      << out;
  EXPECT_NE(out.find("| results | dataset | object | targets | found | ADD-S AUC"),
            std::string::npos)
      << out;

  const auto targets = test::readCsv(root_ / "targets.csv");
  ASSERT_EQ(targets.size(), 3u);
  // The exact pose: every error 0.
  for (const char* column : {"add_mm", "adds_mm", "mssd_mm", "rotation_deg", "translation_cm"}) {
    EXPECT_NEAR(number(targets[0], column), 0, 1e-3) << column;
  }
  EXPECT_EQ(targets[0].at("rt_success"), "1");
  EXPECT_EQ(targets[0].at("mssd_success"), "1");
  // Shifted by (3, 4, 0) mm: every model point moves 5 mm.
  EXPECT_NEAR(number(targets[1], "add_mm"), 5, 1e-3);
  EXPECT_NEAR(number(targets[1], "mssd_mm"), 5, 1e-3);
  EXPECT_NEAR(number(targets[1], "translation_cm"), 0.5, 1e-4);
  EXPECT_NEAR(number(targets[1], "rotation_deg"), 0, 1e-3);
  EXPECT_LE(number(targets[1], "adds_mm"), 5 + 1e-3);
  // Turned by 33 degrees about the object's x axis: roll 33, pitch and yaw 0.
  EXPECT_NEAR(number(targets[2], "rotation_deg"), 11, 1e-3);
  EXPECT_NEAR(number(targets[2], "translation_cm"), 0, 1e-4);
  EXPECT_EQ(targets[2].at("rt_success"), "0");

  const auto summary = test::readCsv(root_ / "summary.csv");
  ASSERT_EQ(summary.size(), 7u);  // object and dataset rows per results file, then overall
  EXPECT_EQ(summary[1].at("object"), "all");
  EXPECT_NEAR(number(summary[1], "adds_auc"), 1, 1e-5);
  EXPECT_NEAR(number(summary[3], "adds_auc"), 1 - number(targets[1], "adds_mm") / 100, 1e-6);
  EXPECT_EQ(summary[6].at("results"), "all");
  EXPECT_EQ(summary[6].at("targets"), "3");
  EXPECT_NEAR(number(summary[6], "rt_success"), 2.0 / 3, 1e-5);
  EXPECT_GT(number(summary[6], "mssd_recall"), 0);
}

TEST_F(EvalCliTest, MissingEstimateIsAFailure) {
  writeBopResults(root_ / "empty.csv", {});
  std::string out;
  ASSERT_EQ(
      test::runCommand(kTool + " eval --dataset " + data() + " --results " +
                           (root_ / "empty.csv").string() + " --csv " + (root_ / "s.csv").string(),
                       out),
      0)
      << out;
  const auto summary = test::readCsv(root_ / "s.csv");
  ASSERT_FALSE(summary.empty());
  EXPECT_EQ(summary[0].at("found"), "0");
  EXPECT_EQ(number(summary[0], "adds_auc"), 0);
  EXPECT_EQ(summary[0].at("median_adds_mm"), "inf");
}

TEST_F(EvalCliTest, BadInputsExitTwoNamingTheProblem) {
  const std::string good = results("good.csv", Eigen::Vector3d::Zero());
  std::string out;
  std::ofstream(root_ / "bad.csv")
      << "scene_id,im_id,obj_id,score,R,t,time\n0,0,1,1,1 0 0,0 0 0,1\n";
  EXPECT_EQ(
      test::runCommand(
          kTool + " eval --dataset " + data() + " --results " + (root_ / "bad.csv").string(), out),
      2);
  EXPECT_NE(out.find("bad.csv:2: R must hold 9 numbers"), std::string::npos) << out;

  BopResult unknown;
  unknown.obj_id = 7;
  writeBopResults(root_ / "unknown.csv", {unknown});
  EXPECT_EQ(test::runCommand(kTool + " eval --dataset " + data() + " --results " +
                                 (root_ / "unknown.csv").string(),
                             out),
            2);
  EXPECT_NE(out.find("unknown object 7"), std::string::npos) << out;

  EXPECT_EQ(
      test::runCommand(
          kTool + " eval --dataset " + data() + " --dataset " + data() + " --results " + good, out),
      2);
  EXPECT_NE(out.find("come in pairs: got 2 datasets and 1 results files"), std::string::npos)
      << out;
  EXPECT_EQ(test::runCommand(
                kTool + " eval --dataset " + data() + " --results " + good + " --prob x", out),
            2);
  EXPECT_NE(out.find("unknown probability source 'x'"), std::string::npos) << out;
}

TEST_F(EvalCliTest, EstimateRecordsEveryAttemptedObject) {
  std::string out;
  ASSERT_EQ(test::runCommand(kTool + " estimate --dataset " + data() + " --out " +
                                 (root_ / "r.csv").string() + " --per-object " +
                                 (root_ / "objects.csv").string() + " --no-cache --bases 20",
                             out),
            0)
      << out;
  const auto rows = test::readCsv(root_ / "objects.csv");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].at("obj_id"), "1");
  EXPECT_EQ(rows[0].at("found"), "1");
  EXPECT_GT(number(rows[0], "seconds"), 0);
  EXPECT_GT(number(rows[0], "cpu_seconds"), 0);
  EXPECT_GT(number(rows[0], "segment_points"), 50);

  // The pose's covariance, 36 numbers: symmetric, positive variances, and `stocs eval
  // --per-object` checks the true error against it.
  std::istringstream entries(rows[0].at("covariance"));
  std::vector<double> c{std::istream_iterator<double>(entries), std::istream_iterator<double>()};
  ASSERT_EQ(c.size(), 36u) << rows[0].at("covariance");
  for (int i = 0; i < 6; ++i) {
    EXPECT_GT(c[static_cast<size_t>(7 * i)], 0) << i;
    for (int j = 0; j < 6; ++j)
      EXPECT_EQ(c[static_cast<size_t>(6 * i + j)], c[static_cast<size_t>(6 * j + i)]);
  }
  ASSERT_EQ(test::runCommand(kTool + " eval --dataset " + data() + " --results " +
                                 (root_ / "r.csv").string() + " --per-object " +
                                 (root_ / "objects.csv").string(),
                             out),
            0)
      << out;
  EXPECT_NE(out.find("covariance: of the true errors of 1 correct poses"), std::string::npos)
      << out;
  EXPECT_EQ(test::runCommand(kTool + " eval --dataset " + data() + " --results " +
                                 (root_ / "r.csv").string() + " --per-object " +
                                 (root_ / "r.csv").string(),
                             out),
            2);
  EXPECT_NE(out.find("r.csv:2: expected 15 comma-separated numbers and a covariance of 36"),
            std::string::npos)
      << out;
  // The pose's confidence evidence and confidence, each in [0, 1], for `stocs calibrate`.
  for (const char* column : {"surface_confirmed", "free_space", "map_support", "matched",
                             "consensus", "explained", "confidence"}) {
    EXPECT_GE(number(rows[0], column), 0) << column;
    EXPECT_LE(number(rows[0], column), 1) << column;
  }
  // A pose in plain view: its surface is confirmed, not in free space, and agreed on.
  EXPECT_GT(number(rows[0], "surface_confirmed"), 0.5);
  EXPECT_LT(number(rows[0], "free_space"), 0.1);
  EXPECT_GT(number(rows[0], "consensus"), 0.5);
}

TEST_F(EvalCliTest, EstimateWritesTheConfidenceAsScoreAndLeavesRejectedPosesOut) {
  const std::string base = kTool + " estimate --dataset " + data() + " --no-cache --bases 20 " +
                           "--per-object " + (root_ / "objects.csv").string() + " --out ";
  std::string out;
  ASSERT_EQ(test::runCommand(base + (root_ / "all.csv").string() + " --min-confidence 0", out), 0)
      << out;
  const std::vector<BopResult> all = readBopResults(root_ / "all.csv");
  ASSERT_EQ(all.size(), 1u);
  const double confidence = number(test::readCsv(root_ / "objects.csv").at(0), "confidence");
  EXPECT_NEAR(all[0].score, confidence, 1e-4);
  EXPECT_NE(out.find("confidence "), std::string::npos) << out;
  // Above the pose's confidence, the pose is rejected: reported with its reason, not written.
  ASSERT_EQ(test::runCommand(base + (root_ / "none.csv").string() + " --min-confidence 1", out), 0)
      << out;
  EXPECT_TRUE(readBopResults(root_ / "none.csv").empty());
  EXPECT_NE(out.find("rejected: confidence "), std::string::npos) << out;
  EXPECT_NE(out.find("1 of 1 objects found, 1 poses rejected below min_confidence"),
            std::string::npos)
      << out;
}

/// Per-object rows (evidence: surface_confirmed = x, the rest 0.5) and targets rows labelled right
/// for x above 0.5, except every tenth, for `stocs calibrate`.
void writeLabelledRun(const std::filesystem::path& objects, const std::filesystem::path& targets,
                      int rows) {
  std::ofstream o(objects), t(targets);
  o << "scene_id,im_id,obj_id,found,seconds,cpu_seconds,segment_points,hypotheses,"
       "surface_confirmed,free_space,map_support,matched,consensus,explained,confidence,"
       "covariance\n";
  t << "results,dataset,scene_id,im_id,obj_id,found,adds_success\n";
  std::string zeros;  // a covariance of 36 zeros
  for (int k = 0; k < 36; ++k) zeros += k ? " 0" : "0";
  for (int i = 0; i < rows; ++i) {
    const double x = (i + 0.5) / rows;
    o << "0," << i << ",1,1,0.01,0.01,100,10," << x << ",0.5,0.5,0.5,0.5,0,0," << zeros << "\n";
    t << "r,d,0," << i << ",1,1," << ((x > 0.5) != (i % 10 == 0) ? 1 : 0) << "\n";
  }
}

TEST_F(EvalCliTest, CalibrateFitsLabelledRunsAndNamesBadInputs) {
  writeLabelledRun(root_ / "o.csv", root_ / "t.csv", 200);
  const std::string pair =
      " --objects " + (root_ / "o.csv").string() + " --targets " + (root_ / "t.csv").string();
  std::string out;
  ASSERT_EQ(test::runCommand(kTool + " calibrate" + pair, out), 0) << out;
  EXPECT_NE(out.find("200 poses, 100 right, 100 wrong"), std::string::npos) << out;
  EXPECT_NE(out.find("estimation:\n  confidence:\n    intercept: "), std::string::npos) << out;
  EXPECT_NE(out.find("  float surface_confirmed = "), std::string::npos) << out;
  EXPECT_NE(out.find("| min_confidence | right poses rejected | wrong poses rejected |"),
            std::string::npos)
      << out;
  // 10% of the labels flipped: the ranking is right for 90% of each class.
  const size_t auc = out.find("ROC AUC ");
  ASSERT_NE(auc, std::string::npos) << out;
  EXPECT_NEAR(std::stod(out.substr(auc + 8)), 0.9, 0.05) << out;
  // Runs on maps from depth alone: the same fit, as the depth_alone coefficients.
  ASSERT_EQ(test::runCommand(kTool + " calibrate --depth-alone" + pair, out), 0) << out;
  EXPECT_NE(out.find("estimation:\n  confidence:\n    depth_alone:\n      intercept: "),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("  ConfidenceModel depth_alone = {"), std::string::npos) << out;

  EXPECT_EQ(test::runCommand(
                kTool + " calibrate" + pair + " --objects " + (root_ / "o.csv").string(), out),
            2);
  EXPECT_NE(out.find("--objects and --targets come in pairs: got 2 per-object files and 1"),
            std::string::npos)
      << out;
  // Exit code and message of `stocs calibrate` on one pair of files in the scratch folder.
  const auto refused = [&](const std::string& objects, const std::string& targets,
                           const std::string& message) {
    EXPECT_EQ(test::runCommand(kTool + " calibrate --objects " + (root_ / objects).string() +
                                   " --targets " + (root_ / targets).string(),
                               out),
              2);
    EXPECT_NE(out.find(message), std::string::npos) << out;
  };
  writeLabelledRun(root_ / "o.csv", root_ / "short.csv", 100);
  writeLabelledRun(root_ / "long.csv", root_ / "t.csv", 200);
  refused("long.csv", "short.csv", "short.csv: no row for scene 0 image 100 object 1 of ");
  std::ofstream(root_ / "bad.csv") << "scene_id,im_id,obj_id,score\n0,0,1,0.5\n";
  refused("long.csv", "bad.csv",
          "bad.csv: no column 'adds_success' (expected `stocs eval --targets-csv`)");
  // A per-object file of the format before the confidence (8 columns).
  std::ofstream(root_ / "old.csv") << "scene_id,im_id,obj_id,found,seconds,cpu_seconds,"
                                      "segment_points,hypotheses\n0,0,1,1,0.1,0.1,100,10\n";
  refused("old.csv", "t.csv", "old.csv:2: expected 15 comma-separated numbers");
  // Only right poses: nothing to tell them from.
  writeLabelledRun(root_ / "one.csv", root_ / "one_t.csv", 2);
  std::ofstream(root_ / "one_t.csv") << "scene_id,im_id,obj_id,adds_success\n0,0,1,1\n0,1,1,1\n";
  refused("one.csv", "one_t.csv", "2 poses of which 2 right: the fit needs right and wrong ones");
}

/// ADD, ADD-S, APC rotation and translation errors of an estimate of an asymmetric object, from
/// their definitions by brute force over the model's vertices: a check independent of the tools.
struct HandMetrics {
  double add_mm = 0, adds_mm = 0, rotation_deg = 0, translation_cm = 0;
};

HandMetrics handMetrics(const MeshData& model, const BopResult& e, const BopGtInstance& g) {
  HandMetrics m;
  for (const Eigen::Vector3f& v : model.vertices) {
    const Eigen::Vector3d x = v.cast<double>() * 1000;
    const Eigen::Vector3d moved = e.R * x + e.t_mm;
    m.add_mm += (moved - (g.R * x + g.t_mm)).norm();
    double closest = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3f& w : model.vertices) {
      closest = std::min(closest, (moved - (g.R * w.cast<double>() * 1000 + g.t_mm)).norm());
    }
    m.adds_mm += closest;
  }
  m.add_mm /= model.vertices.size();
  m.adds_mm /= model.vertices.size();
  // E = Rz(yaw) Ry(pitch) Rx(roll), away from pitch +-90 degrees.
  const Eigen::Matrix3d E = g.R.transpose() * e.R;
  const double roll = std::atan2(E(2, 1), E(2, 2));
  const double pitch = std::asin(std::clamp(-E(2, 0), -1.0, 1.0));
  const double yaw = std::atan2(E(1, 0), E(0, 0));
  m.rotation_deg = (std::abs(roll) + std::abs(pitch) + std::abs(yaw)) / 3 * 180 / M_PI;
  m.translation_cm = (e.t_mm - g.t_mm).norm() / 10;
  return m;
}

bool isPng(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  return std::string(magic, 8) == "\x89PNG\r\n\x1a\n" && std::filesystem::file_size(file) > 2000;
}

using CsvRows = std::vector<std::map<std::string, std::string>>;

/// equal_accuracy.csv against the main and base-count tables: one row per ordered pair of methods,
/// naming the fewest swept bases from which on the AUC reaches the other method's, with the ratio
/// of medians.
void expectFewestBasesAtEqualAccuracy(const std::filesystem::path& out, const CsvRows& summary,
                                      const CsvRows& bases) {
  const auto equal = test::readCsv(out / "equal_accuracy.csv");
  ASSERT_EQ(equal.size(), summary.size() * (summary.size() - 1));
  for (const auto& row : equal) {
    const auto other = std::find_if(summary.begin(), summary.end(), [&](const auto& s) {
      return s.at("method") == row.at("against");
    });
    ASSERT_NE(other, summary.end());
    const double target = number(*other, "adds_auc");
    EXPECT_EQ(number(row, "against_adds_auc"), target);
    std::string fewest = "none";
    const std::map<std::string, std::string>* match = nullptr;
    for (const auto& b : bases) {  // ascending counts: the last run of counts reaching the target
      if (b.at("method") != row.at("method")) continue;
      if (number(b, "adds_auc") < target) {
        fewest = "none";
        match = nullptr;
      } else if (!match) {
        fewest = b.at("bases");
        match = &b;
      }
    }
    ASSERT_EQ(row.at("bases"), fewest) << row.at("method") << " against " << row.at("against");
    if (!match) continue;
    EXPECT_EQ(number(row, "adds_auc"), number(*match, "adds_auc"));
    EXPECT_NEAR(number(row, "time_ratio"),
                number(*other, "time_median_s") / number(*match, "time_median_s"), 1e-6);
    EXPECT_NEAR(number(row, "cpu_ratio"),
                number(*other, "cpu_median_s") / number(*match, "cpu_median_s"), 1e-6);
  }
}

TEST_F(EvalCliTest, BenchRunsMethodsSweepsAndPlots) {
  const std::filesystem::path out = root_ / "bench";
  std::string log;
  // A trailing separator does not change the dataset's name.
  ASSERT_EQ(test::runCommand(kTool + " bench --dataset " + data() + "/ --out " + out.string() +
                                 " --methods stocs,stocs-hard --prob real --thresholds 0.5,0.95 "
                                 "--budgets 0.05 --base-counts 30,5 --bases 30 --cache-dir " +
                                 (root_ / "cache").string(),
                             log),
            0)
      << log;
  // Not a terminal: one line per run.
  EXPECT_NE(log.find("bench [8/12] stocs-hard on data/real, budget 0.05 s: ok"), std::string::npos)
      << log;
  EXPECT_NE(log.find("bench [12/12] stocs-hard on data/real, 30 bases: ok"), std::string::npos)
      << log;

  const auto summary = test::readCsv(out / "summary.csv");
  ASSERT_EQ(summary.size(), 2u) << "one row per method for the single input";
  for (const auto& row : summary) {
    EXPECT_EQ(row.at("dataset"), "data");
    EXPECT_EQ(row.at("source"), "real");
    EXPECT_EQ(row.at("targets"), "1");
    EXPECT_EQ(row.at("failed_runs"), "0");
    EXPECT_GT(number(row, "time_median_s"), 0);
    EXPECT_GT(number(row, "cpu_median_s"), 0);
    EXPECT_GT(number(row, "peak_memory_mb"), 10);
  }
  EXPECT_EQ(summary[0].at("method"), "stocs");
  EXPECT_EQ(summary[0].at("found"), "1");
  EXPECT_EQ(number(summary[0], "adds_success"), 1);  // a clean generated frame
  // The confidence columns: one correct pose and no other target, so no AUC; its score decides
  // whether it is kept at t = 0.5.
  EXPECT_EQ(summary[0].at("absent_targets"), "0");
  EXPECT_EQ(summary[0].at("score_roc_auc"), "");
  EXPECT_EQ(number(summary[0], "correct_rejected_at_t"),
            readBopResults(out / "bop" / "data_real" / "stocs.csv").at(0).score < 0.5 ? 1 : 0);

  // The pose the method wrote is known: the report's metrics of it are exact (to the CSV's 3
  // decimals), computed here from their definitions.
  const std::vector<BopResult> written = readBopResults(out / "bop" / "data_real" / "stocs.csv");
  ASSERT_EQ(written.size(), 1u);
  const BopGtInstance truth = BopDataset(root_ / "data").sceneGroundTruth(0).at(0).at(0);
  const HandMetrics expected = handMetrics(
      loadMesh((root_ / "data" / "models" / "obj_000001.ply").string(), 0.001f), written[0], truth);
  const auto targets = test::readCsv(out / "targets.csv");
  ASSERT_EQ(targets.size(), 2u);
  EXPECT_EQ(targets[0].at("method"), "stocs");
  EXPECT_NEAR(number(targets[0], "add_mm"), expected.add_mm, 6e-4);
  EXPECT_NEAR(number(targets[0], "adds_mm"), expected.adds_mm, 6e-4);
  EXPECT_NEAR(number(targets[0], "rotation_deg"), expected.rotation_deg, 6e-4);
  EXPECT_NEAR(number(targets[0], "translation_cm"), expected.translation_cm, 6e-4);
  EXPECT_NEAR(number(summary[0], "adds_auc"), 1 - expected.adds_mm / 100, 1e-5);
  EXPECT_EQ(targets[0].at("rt_success"),
            expected.rotation_deg < 10 && expected.translation_cm < 2 ? "1" : "0");

  // The sweeps: every method at every value. The map holds 0.9 everywhere on the object, so a
  // threshold of 0.95 leaves no segment and no pose.
  const auto thresholds = test::readCsv(out / "threshold_sweep.csv");
  ASSERT_EQ(thresholds.size(), 4u);
  EXPECT_EQ(thresholds[0].at("threshold"), "0.5");
  EXPECT_EQ(thresholds[0].at("found"), "1");
  EXPECT_EQ(thresholds[1].at("threshold"), "0.95");
  EXPECT_EQ(thresholds[1].at("found"), "0");
  EXPECT_EQ(test::readCsv(out / "budget_sweep.csv").size(), 2u);
  const auto bases = test::readCsv(out / "bases_sweep.csv");
  ASSERT_EQ(bases.size(), 4u);
  EXPECT_EQ(bases[0].at("bases"), "5");  // ascending, whatever the order given
  EXPECT_EQ(bases[1].at("bases"), "30");
  expectFewestBasesAtEqualAccuracy(out, summary, bases);

  for (const char* plot : {"accuracy_threshold_data_real.png", "reliability_data_real.png",
                           "threshold_sweep_data_real.png", "budget_sweep_data_real.png",
                           "bases_sweep_data_real.png"}) {
    EXPECT_TRUE(isPng(out / "plots" / plot)) << plot;
  }
  std::ifstream md(out / "results.md");
  const std::string report((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  EXPECT_NE(report.find("## Methods x datasets"), std::string::npos);
  // The command as given, lists as typed.
  EXPECT_NE(report.find("--methods stocs,stocs-hard"), std::string::npos) << report;
  EXPECT_NE(report.find("--thresholds 0.5,0.95 --budgets 0.05"), std::string::npos) << report;
  EXPECT_NE(report.find("![accuracy_threshold, data/real](plots/accuracy_threshold_data_real.png)"),
            std::string::npos);
  EXPECT_EQ(report.find("## Notes and failures"), std::string::npos) << report;
  // Every run began with an untimed estimate of its first object, and the report says so.
  EXPECT_NE(report.find("once, untimed"), std::string::npos) << report;
  int logs = 0, warmed = 0;
  for (const auto& f : std::filesystem::recursive_directory_iterator(out)) {
    if (f.path().extension() != ".log") continue;
    std::ifstream in(f.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ++logs;
    warmed += text.find("estimated once, untimed") != std::string::npos;
  }
  EXPECT_EQ(logs, 12);
  EXPECT_EQ(warmed, logs);
}

TEST_F(EvalCliTest, BenchSurvivesAFailingRun) {
  const std::filesystem::path out = root_ / "bench";
  // A folder where the results file should go makes that run fail to write them.
  std::filesystem::create_directories(out / "bop" / "data_real" / "stocs.csv" / "blocker");
  std::string log;
  ASSERT_EQ(bench("--methods stocs,stocs-hard --no-threshold-sweep --no-budget-sweep "
                  "--no-bases-sweep --no-plots --bases 20 --no-cache",
                  log),
            0)
      << log;
  EXPECT_NE(log.find("stocs on data/real: FAILED: exit code 2"), std::string::npos) << log;
  const auto summary = test::readCsv(out / "summary.csv");
  ASSERT_EQ(summary.size(), 2u);
  EXPECT_EQ(summary[0].at("failed_runs"), "1");
  EXPECT_EQ(summary[0].at("found"), "0");
  EXPECT_EQ(number(summary[0], "adds_auc"), 0);
  EXPECT_EQ(summary[1].at("found"), "1");  // the next method ran anyway
  EXPECT_FALSE(std::filesystem::exists(out / "plots"));
}

TEST_F(EvalCliTest, BenchSweepsOnlyTheSweepMethods) {
  const std::filesystem::path out = root_ / "bench";
  std::string log;
  ASSERT_EQ(bench("--methods stocs,stocs-hard --sweep-methods stocs-hard --thresholds 0.5 "
                  "--no-budget-sweep --base-counts 10 --no-plots --bases 20 --no-cache",
                  log),
            0)
      << log;
  EXPECT_NE(log.find("bench [4/4] stocs-hard on data/real, 10 bases: ok"), std::string::npos)
      << log;
  const auto thresholds = test::readCsv(out / "threshold_sweep.csv");
  ASSERT_EQ(thresholds.size(), 1u);
  EXPECT_EQ(thresholds[0].at("method"), "stocs-hard");
  const auto bases = test::readCsv(out / "bases_sweep.csv");
  ASSERT_EQ(bases.size(), 1u);
  EXPECT_EQ(bases[0].at("method"), "stocs-hard");
  const auto equal = test::readCsv(out / "equal_accuracy.csv");
  ASSERT_EQ(equal.size(), 1u);
  EXPECT_EQ(equal[0].at("method"), "stocs-hard");
  EXPECT_EQ(equal[0].at("against"), "stocs");
  EXPECT_FALSE(std::filesystem::exists(out / "budget_sweep.csv"));
}

TEST_F(EvalCliTest, BenchKillsARunPastItsTimeout) {
  const std::filesystem::path out = root_ / "bench";
  std::string log;
  ASSERT_EQ(bench("--methods stocs --no-threshold-sweep --no-budget-sweep --no-bases-sweep "
                  "--no-plots --no-cache --run-timeout 0.01",
                  log),
            0)
      << log;
  EXPECT_NE(log.find("stocs on data/real: FAILED: timed out (limit 0.01 s)"), std::string::npos)
      << log;
  const auto summary = test::readCsv(out / "summary.csv");
  ASSERT_EQ(summary.size(), 1u);
  EXPECT_EQ(summary[0].at("failed_runs"), "1");
}

TEST_F(EvalCliTest, BenchRefusesUnknownMethodsAndSources) {
  std::string log;
  const std::string base =
      kTool + " bench --dataset " + data() + " --out " + (root_ / "b").string() + " --no-plots";
  EXPECT_EQ(test::runCommand(base + " --methods stocs,nope", log), 2);
  EXPECT_NE(log.find("unknown method 'nope'"), std::string::npos) << log;
  EXPECT_EQ(test::runCommand(base + " --prob nope", log), 2);
  EXPECT_NE(log.find("unknown probability source 'nope'"), std::string::npos) << log;
  EXPECT_EQ(test::runCommand(base + " --thresholds 1.5", log), 2);
  EXPECT_NE(log.find("threshold 1.5 is outside (0, 1)"), std::string::npos) << log;
  EXPECT_EQ(test::runCommand(base + " --base-counts 10,0", log), 2);
  EXPECT_NE(log.find("base count 0 is outside [1, 1000000]"), std::string::npos) << log;
  EXPECT_EQ(test::runCommand(base + " --methods stocs --sweep-methods ppf", log), 2);
  EXPECT_NE(log.find("sweep method 'ppf' is not one of the methods run"), std::string::npos) << log;
  const std::string missing = (root_ / "missing").string();
  EXPECT_EQ(test::runCommand(kTool + " bench --dataset " + missing + " --out " +
                                 (root_ / "b").string() + " --no-plots",
                             log),
            2);
  EXPECT_NE(log.find("dataset " + missing + ": not a folder"), std::string::npos) << log;
  EXPECT_NE(test::runCommand(kTool + " bench --out " + (root_ / "b").string(), log), 0);
  EXPECT_NE(log.find("--dataset is required"), std::string::npos) << log;
}

TEST(BenchHelp, ShowsTheDefaultOfEveryOptionWithAValue) {
  // CLI11's type names of options that take a value (std::regex here drew a GCC false positive,
  // -Wmaybe-uninitialized inside <functional>, in the sanitizer build).
  const char* const kValueTypes[] = {" TEXT", " INT", " UINT", " FLOAT", " BOOLEAN"};
  std::string help;
  ASSERT_EQ(test::runCommand(kTool + " bench --help", help), 0);
  std::istringstream lines(help);
  int options = 0;
  for (std::string line; std::getline(lines, line);) {
    const size_t name = line.find("--");
    if (name == std::string::npos || line.find_first_not_of(' ') != name) continue;
    const bool takes_value =
        std::any_of(std::begin(kValueTypes), std::end(kValueTypes),
                    [&](const char* type) { return line.find(type) != std::string::npos; });
    if (!takes_value || line.find("REQUIRED") != std::string::npos) continue;
    ++options;
    EXPECT_NE(line.find('='), std::string::npos) << "no default shown: " << line;
  }
  EXPECT_GT(options, 30) << help;  // bench's own options and every forwarded estimation option
}

}  // namespace
}  // namespace stocs
