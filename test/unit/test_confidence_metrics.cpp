// Confidence metrics on hand-made targets: ROC AUC of perfect, reversed, random and tied
// rankings, the calibration error of calibrated and overconfident scores, and the figures at a
// threshold.
#include <gtest/gtest.h>

#include <cmath>

#include "stocs/eval/confidence_metrics.h"
#include "stocs/util/random.h"

namespace stocs {
namespace {

ScoredTarget pose(double score, bool correct) {
  return {true, score, correct, false};
}

TEST(ConfidenceMetrics, RocAucOfPerfectReversedTiedAndRandomRankings) {
  EXPECT_DOUBLE_EQ(rocAuc({0.9, 0.8}, {0.1, 0.2, 0.3}), 1.0);
  EXPECT_DOUBLE_EQ(rocAuc({0.1, 0.2}, {0.8, 0.9}), 0.0);
  EXPECT_DOUBLE_EQ(rocAuc({0.5, 0.5}, {0.5}), 0.5);
  EXPECT_DOUBLE_EQ(rocAuc({0.5, 0.9}, {0.5, 0.1}), (1.5 + 2.0) / 4);
  EXPECT_TRUE(std::isnan(rocAuc({}, {0.3})));
  Rng rng(3);
  std::vector<double> a, b;
  for (int i = 0; i < 4000; ++i) (i % 2 ? a : b).push_back(uniform01(rng));
  EXPECT_NEAR(rocAuc(a, b), 0.5, 0.03);
}

TEST(ConfidenceMetrics, TargetsWithoutAPoseRankBelowEveryScore) {
  // Correct poses score 0.1; wrong ones are missing poses and an absent object left alone.
  const std::vector<ScoredTarget> targets = {
      pose(0.1, true), pose(0.1, true), {}, {}, {false, 0, false, true}};
  EXPECT_DOUBLE_EQ(confidenceMetrics(targets, 0.5).roc_auc, 1.0);
  // A negative baseline score still ranks above no pose.
  EXPECT_DOUBLE_EQ(confidenceMetrics({pose(-3, true), {}}, 0.5).roc_auc, 1.0);
}

TEST(ConfidenceMetrics, CalibratedScoresHaveASmallErrorAndOverconfidentOnesALargeOne) {
  Rng rng(7);
  std::vector<ScoredTarget> calibrated, overconfident;
  for (int i = 0; i < 20000; ++i) {
    const double p = uniform01(rng);
    const bool correct = uniform01(rng) < p;
    calibrated.push_back(pose(p, correct));
    overconfident.push_back(pose(std::min(1.0, 0.5 + p), correct));
  }
  const ConfidenceMetrics good = confidenceMetrics(calibrated, 0.5);
  EXPECT_LT(good.ece, 0.02);
  ASSERT_EQ(good.reliability.size(), 10u);
  for (const ReliabilityBin& b : good.reliability) {
    EXPECT_NEAR(b.mean_score, (b.lo + b.hi) / 2, 0.01);
    EXPECT_NEAR(b.share_correct, b.mean_score, 0.05);
    EXPECT_GT(b.count, 1500);
  }
  EXPECT_GT(confidenceMetrics(overconfident, 0.5).ece, 0.3);
  // Scores outside [0, 1] have no calibration.
  const ConfidenceMetrics raw = confidenceMetrics({pose(3, true), pose(0.5, false)}, 0.5);
  EXPECT_TRUE(std::isnan(raw.ece));
  EXPECT_TRUE(raw.reliability.empty());
}

TEST(ConfidenceMetrics, FiguresAtTheThresholdCountAbsentObjectsAndRejections) {
  const std::vector<ScoredTarget> targets = {
      pose(0.9, true),          pose(0.7, true),
      pose(0.3, true),                                     // one correct pose rejected
      pose(0.8, false),         pose(0.2, false),          // a wrong pose kept
      {true, 0.6, false, true}, {true, 0.1, false, true},  // absent, one kept
      {false, 0, false, true},  {},                        // no pose
  };
  const ConfidenceMetrics m = confidenceMetrics(targets, 0.5);
  EXPECT_EQ(m.targets, 9);
  EXPECT_EQ(m.absent, 3);
  EXPECT_EQ(m.poses, 7);
  EXPECT_EQ(m.correct, 3);
  EXPECT_DOUBLE_EQ(m.precision, 2.0 / 4);         // 0.9, 0.7 of 0.9, 0.7, 0.8, 0.6
  EXPECT_DOUBLE_EQ(m.recall, 2.0 / 6);            // six targets whose object is present
  EXPECT_DOUBLE_EQ(m.absent_posed, 1.0 / 3);      // 0.6
  EXPECT_DOUBLE_EQ(m.correct_rejected, 1.0 / 3);  // 0.3
  // Correct 0.9, 0.7, 0.3 against 0.8, 0.2, 0.6, 0.1 and two without a pose.
  EXPECT_DOUBLE_EQ(m.roc_auc, (6 + 5 + 4) / 18.0);
  const ConfidenceMetrics none = confidenceMetrics({pose(0.9, true)}, 0.5);
  EXPECT_TRUE(std::isnan(none.absent_posed));
  EXPECT_TRUE(std::isnan(none.roc_auc));
}

}  // namespace
}  // namespace stocs
