// BOP targets files end to end: `stocs synth` writes one with absent objects, `stocs estimate
// --targets` estimates exactly its targets, absent ones included, and `stocs eval --targets`
// counts a pose of an absent object as a false positive in its confidence figures (exact on
// hand-made results). Bad targets files exit 2 naming the file and the target.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>

#include "stocs/io/bop_dataset.h"
#include "stocs/io/bop_results.h"
#include "stocs/io/bop_targets.h"
#include "test_support.h"

namespace stocs {
namespace {
namespace fs = std::filesystem;

const std::string kTool = STOCS_TOOL_PATH;

/// The column `column` of every row of a CSV file ("" where a row has none).
std::vector<std::string> csvColumn(const fs::path& file, const std::string& column) {
  std::vector<std::string> values;
  for (const auto& row : test::readCsv(file)) {
    const auto cell = row.find(column);
    values.push_back(cell == row.end() ? "" : cell->second);
  }
  return values;
}

/// A generated scene of 2 objects and 2 absent ones, made once for every test.
class CliTargets : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(test::scratchDir("cli_targets"));
    std::string out;
    ASSERT_EQ(test::runCommand(kTool + " synth --out " + data() +
                                   " --objects 2 --distractors 1 --absent 2 --seed 6 --quiet",
                               out),
              0)
        << out;
  }
  static void TearDownTestSuite() { delete root_; }

  static std::string data() { return (*root_ / "data").string(); }
  static std::string targetsFile() {
    return (*root_ / "data" / "test_targets_bop19.json").string();
  }

  static fs::path* root_;
};
fs::path* CliTargets::root_ = nullptr;

TEST_F(CliTargets, SynthWritesTwoPresentAndTwoAbsentTargets) {
  const std::vector<BopTarget> targets = readBopTargets(targetsFile());
  ASSERT_EQ(targets.size(), 4u);
  int absent = 0;
  for (const BopTarget& t : targets) {
    absent += t.inst_count == 0;
    EXPECT_TRUE(fs::exists(BopDataset(data()).probabilityPath(0, 0, t.obj_id))) << t.obj_id;
  }
  EXPECT_EQ(absent, 2);
}

TEST_F(CliTargets, EvalCountsAPoseOfAnAbsentObjectAsAFalsePositive) {
  // The present objects at their true poses (score 0.9); one absent object posed at 0.8.
  const BopDataset dataset(data());
  std::vector<BopResult> rows;
  const std::map<int, std::vector<BopGtInstance>> gt = dataset.sceneGroundTruth(0);
  for (const BopGtInstance& g : gt.at(0)) {
    rows.push_back({0, 0, g.obj_id, 0.9, g.R, g.t_mm, 1.0});
  }
  for (const BopTarget& t : readBopTargets(targetsFile())) {
    if (t.inst_count == 0) {
      rows.push_back({0, 0, t.obj_id, 0.8, rows[0].R, rows[0].t_mm, 1.0});
      break;
    }
  }
  const fs::path results = *root_ / "handmade.csv";
  writeBopResults(results, rows);
  std::string out;
  const fs::path summary = *root_ / "summary.csv", per_target = *root_ / "targets.csv";
  ASSERT_EQ(test::runCommand(kTool + " eval --dataset " + data() + " --results " +
                                 results.string() + " --targets " + targetsFile() + " --csv " +
                                 summary.string() + " --targets-csv " + per_target.string(),
                             out),
            0)
      << out;
  EXPECT_EQ(csvColumn(per_target, "obj_id").size(), 4u);
  const std::vector<std::string> objects = csvColumn(summary, "object");
  ASSERT_EQ(objects.back(), "all");
  const auto last = [&](const std::string& column) { return csvColumn(summary, column).back(); };
  EXPECT_EQ(last("targets"), "2");  // accuracy over the present objects
  EXPECT_EQ(last("found"), "2");
  EXPECT_DOUBLE_EQ(std::stod(last("adds_success")), 1.0);
  EXPECT_EQ(last("absent_targets"), "2");
  EXPECT_DOUBLE_EQ(std::stod(last("score_roc_auc")), 1.0);  // 0.9, 0.9 above 0.8 and no pose
  EXPECT_NEAR(std::stod(last("ece")), (2 * 0.1 + 0.8) / 3, 1e-6);
  EXPECT_NEAR(std::stod(last("precision_at_t")), 2.0 / 3, 1e-6);
  EXPECT_DOUBLE_EQ(std::stod(last("recall_at_t")), 1.0);
  EXPECT_DOUBLE_EQ(std::stod(last("absent_posed_at_t")), 0.5);
  EXPECT_DOUBLE_EQ(std::stod(last("correct_rejected_at_t")), 0.0);
  // Above the absent pose's score it is rejected; below the correct ones' they are too.
  ASSERT_EQ(test::runCommand(kTool + " eval --dataset " + data() + " --results " +
                                 results.string() + " --targets " + targetsFile() +
                                 " --min-confidence 0.95 --csv " + summary.string(),
                             out),
            0)
      << out;
  EXPECT_DOUBLE_EQ(std::stod(last("absent_posed_at_t")), 0.0);
  EXPECT_DOUBLE_EQ(std::stod(last("correct_rejected_at_t")), 1.0);
  EXPECT_NE(out.find("| [0.9, 1.0] | 2 | 0.900 | 100.0% |"), std::string::npos) << out;
}

TEST_F(CliTargets, EstimateAttemptsExactlyTheTargetsAbsentOnesIncluded) {
  const fs::path results = *root_ / "estimated.csv";
  std::string out;
  ASSERT_EQ(test::runCommand(kTool + " estimate --dataset " + data() + " --out " +
                                 results.string() + " --targets " + targetsFile() +
                                 " --bases 20 --per-object " + (*root_ / "runs.csv").string(),
                             out),
            0)
      << out;
  std::multiset<std::string> attempted, expected;
  for (const std::string& obj : csvColumn(*root_ / "runs.csv", "obj_id")) attempted.insert(obj);
  for (const BopTarget& t : readBopTargets(targetsFile())) {
    expected.insert(std::to_string(t.obj_id));
  }
  EXPECT_EQ(attempted, expected) << out;
  // Without --targets, the objects of scene_gt.json only.
  ASSERT_EQ(
      test::runCommand(kTool + " estimate --dataset " + data() + " --out " + results.string() +
                           " --bases 20 --per-object " + (*root_ / "runs.csv").string(),
                       out),
      0)
      << out;
  EXPECT_EQ(csvColumn(*root_ / "runs.csv", "obj_id").size(), 2u) << out;
}

TEST_F(CliTargets, BadTargetsFilesExitTwoNamingTheFileAndTheTarget) {
  const fs::path bad = *root_ / "bad_targets.json";
  int present = 0, absent = 0;
  for (const BopTarget& t : readBopTargets(targetsFile())) {
    (t.inst_count ? present : absent) = t.obj_id;
  }
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"([{"scene_id": 0, "im_id": 0, "obj_id": 1}])",
       bad.string() + ": entry 0: missing key 'inst_count'"},
      {fmt::format(R"([{{"scene_id": 0, "im_id": 0, "obj_id": {}, "inst_count": 0}}])", present),
       fmt::format("{}: target scene 0 image 0 object {}: inst_count is 0 but scene_gt.json has "
                   "the object there",
                   bad.string(), present)},
      {R"([{"scene_id": 7, "im_id": 0, "obj_id": 1, "inst_count": 1}])",
       bad.string() + ": target scene 7 image 0 object 1: the scene is not in dataset"},
      {R"([{"scene_id": 0, "im_id": 5, "obj_id": 1, "inst_count": 1}])",
       bad.string() + ": target scene 0 image 5 object 1: the image has no entry in scene_gt.json"},
  };
  for (const auto& [text, message] : cases) {
    std::ofstream(bad) << text;
    for (const std::string command : {"estimate", "eval"}) {
      std::string out;
      const std::string output = command == "estimate" ? " --out " : " --results ";
      EXPECT_EQ(
          test::runCommand(kTool + " " + command + " --dataset " + data() + output +
                               (*root_ / "unused.csv").string() + " --targets " + bad.string(),
                           out),
          2)
          << command << ": " << out;
      EXPECT_NE(out.find(message), std::string::npos) << command << ": " << out;
    }
  }
  // A target whose map the source cannot give.
  std::ofstream(bad) << fmt::format(
      R"([{{"scene_id": 0, "im_id": 0, "obj_id": {}, "inst_count": 0}}])", absent);
  const fs::path map = BopDataset(data()).probabilityPath(0, 0, absent);
  fs::rename(map, *root_ / "kept.png");
  std::string out;
  EXPECT_EQ(test::runCommand(kTool + " estimate --dataset " + data() + " --out " +
                                 (*root_ / "unused.csv").string() + " --targets " + bad.string(),
                             out),
            2);
  fs::rename(*root_ / "kept.png", map);
  EXPECT_NE(out.find(fmt::format("target scene 0 image 0 object {} has no probability map from "
                                 "source 'real'",
                                 absent)),
            std::string::npos)
      << out;
}

}  // namespace
}  // namespace stocs
