// The `stocs` tool end to end: results on a generated dataset, --help, and error exits.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "stocs/io/bop_results.h"
#include "test_support.h"

namespace stocs {
namespace {

const std::string kTool = STOCS_TOOL_PATH;

TEST(Cli, EstimateWritesBopResultsCloseToTheTruth) {
  const auto root = test::scratchDir("cli_estimate");
  const Eigen::Isometry3f truth = test::writeSyntheticBopDataset(root / "data");
  std::string out;
  const int rc =
      test::runCommand(kTool + " estimate --dataset " + (root / "data").string() + " --out " +
                           (root / "r.csv").string() + " --cache-dir " + (root / "cache").string(),
                       out);
  ASSERT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("1 of 1 objects found"), std::string::npos) << out;
  const std::vector<BopResult> results = readBopResults(root / "r.csv");
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].obj_id, 1);
  EXPECT_LT((results[0].t_mm - truth.translation().cast<double>() * 1000).norm(), 5.0);
  EXPECT_LT(Eigen::AngleAxisd(results[0].R.transpose() * truth.linear().cast<double>()).angle(),
            0.05);
  EXPECT_GT(results[0].time, 0.0);

  // A warm-up estimate before the timed one changes no result.
  ASSERT_EQ(test::runCommand(kTool + " estimate --warm-up --dataset " + (root / "data").string() +
                                 " --out " + (root / "w.csv").string() + " --cache-dir " +
                                 (root / "cache").string(),
                             out),
            0)
      << out;
  EXPECT_NE(out.find("warm-up: object 1 of scene 0 image 0 estimated once, untimed"),
            std::string::npos)
      << out;
  const std::vector<BopResult> warm = readBopResults(root / "w.csv");
  ASSERT_EQ(warm.size(), 1u);
  EXPECT_EQ(warm[0].R, results[0].R);
  EXPECT_EQ(warm[0].t_mm, results[0].t_mm);

  // Repeats only change the times: the same pose, and one per-object row per target.
  ASSERT_EQ(test::runCommand(kTool + " estimate --warm-up --repeats 3 --dataset " +
                                 (root / "data").string() + " --out " + (root / "x.csv").string() +
                                 " --per-object " + (root / "x_objects.csv").string() +
                                 " --cache-dir " + (root / "cache").string(),
                             out),
            0)
      << out;
  const std::vector<BopResult> repeated = readBopResults(root / "x.csv");
  ASSERT_EQ(repeated.size(), 1u);
  EXPECT_EQ(repeated[0].R, results[0].R);
  EXPECT_EQ(repeated[0].t_mm, results[0].t_mm);
  EXPECT_GT(repeated[0].time, 0.0);
  std::ifstream rows(root / "x_objects.csv");
  std::string line;
  int lines = 0;
  while (std::getline(rows, line)) ++lines;
  EXPECT_EQ(lines, 2);  // header and the one target
}

TEST(Cli, EveryRegisteredMethodRunsAndUnknownOnesAreRefused) {
  const auto root = test::scratchDir("cli_methods");
  test::writeSyntheticBopDataset(root / "data");
  std::string out;
  const std::string base = kTool + " estimate --dataset " + (root / "data").string() + " --out " +
                           (root / "r.csv").string() + " --no-cache --bases 30";
  ASSERT_EQ(test::runCommand(base + " --method stocs-hard", out), 0) << out;
  EXPECT_NE(out.find("1 of 1 objects found"), std::string::npos) << out;
  EXPECT_EQ(test::runCommand(base + " --method nope", out), 2);
  EXPECT_NE(out.find("unknown method 'nope'; known methods: "), std::string::npos) << out;
  EXPECT_NE(test::runCommand(base + " --hard-threshold 1.5", out), 0);
}

TEST(Cli, HelpListsEveryOptionWithItsDefault) {
  std::string out;
  ASSERT_EQ(test::runCommand(kTool + " estimate --help", out), 0);
  for (const char* expected :
       {"--bases", "--time-budget", "--seed", "--threads", "--epsilon", "--delta-s", "--delta-n",
        "--wide-angle", "--coplanarity", "--scenes", "--objects", "=100"}) {
    EXPECT_NE(out.find(expected), std::string::npos) << expected << " missing from:\n" << out;
  }
}

TEST(Cli, BadInputsExitNonZeroWithAMessage) {
  const auto root = test::scratchDir("cli_errors");
  std::string out;
  EXPECT_EQ(test::runCommand(kTool + " estimate --dataset /nonexistent --out x.csv", out), 2);
  EXPECT_NE(out.find("/nonexistent: not a folder"), std::string::npos) << out;
  test::writeSyntheticBopDataset(root / "data");
  EXPECT_NE(test::runCommand(kTool + " estimate --dataset " + (root / "data").string() +
                                 " --out x.csv --bases 0",
                             out),
            0);
  EXPECT_NE(out.find("bases 0"), std::string::npos) << out;
  EXPECT_EQ(test::runCommand(kTool + " estimate --dataset " + (root / "data").string() +
                                 " --out x.csv --samples-per-voxel 0.5",
                             out),
            2);
  EXPECT_NE(out.find("--samples-per-voxel 0.5 is outside 0 or [1, 100]"), std::string::npos) << out;
  EXPECT_EQ(test::runCommand(kTool + " estimate --dataset " + (root / "data").string() +
                                 " --out x.csv --focus-exponent 0",
                             out),
            2);
  EXPECT_NE(out.find("--focus-exponent 0 is outside [1, 16]"), std::string::npos) << out;
  EXPECT_EQ(test::runCommand(kTool + " estimate --dataset " + (root / "data").string() +
                                 " --out x.csv --scenes 9",
                             out),
            2);
  EXPECT_NE(out.find("scene 9 does not exist"), std::string::npos) << out;
  EXPECT_EQ(test::runCommand(kTool + " estimate --dataset " + (root / "data").string() +
                                 " --out x.csv --objects 5",
                             out),
            2);
  EXPECT_NE(out.find("no (image, object) pair"), std::string::npos) << out;
  EXPECT_NE(test::runCommand(kTool + " estimate --dataset " + (root / "data").string() +
                                 " --out x.csv --repeats 0",
                             out),
            0);
  EXPECT_NE(out.find("--repeats"), std::string::npos) << out;
  EXPECT_NE(test::runCommand(kTool + " estimate --dataset " + (root / "data").string(), out),
            0);  // --out missing
  EXPECT_NE(test::runCommand(kTool + " frobnicate", out), 0);
}

}  // namespace
}  // namespace stocs
