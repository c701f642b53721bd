// Summaries of target errors: success rates, AUC and medians with missing estimates.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "stocs/eval/metric_summary.h"

namespace stocs {
namespace {

const double kInf = std::numeric_limits<double>::infinity();

TargetErrors found(double adds, double add, double rotation, double translation, bool symmetric) {
  TargetErrors e;
  e.found = true;
  e.instance = 0;
  e.adds_mm = adds;
  e.add_mm = add;
  e.rotation_deg = rotation;
  e.translation_mm = translation;
  e.diameter_mm = 100;
  e.symmetric = symmetric;
  return e;
}

TargetErrors missing() {
  TargetErrors e;
  e.diameter_mm = 100;
  return e;
}

TEST(Quantile, LinearBetweenOrderStatistics) {
  EXPECT_DOUBLE_EQ(quantile({3, 1, 2}, 0.5), 2);
  EXPECT_DOUBLE_EQ(quantile({4, 1, 3, 2}, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(quantile({4, 1, 3, 2}, 0.9), 3.7);  // position 2.7
  EXPECT_DOUBLE_EQ(quantile({1, 2, kInf}, 0.5), 2);
  EXPECT_TRUE(std::isinf(quantile({1, kInf}, 0.5)));
  EXPECT_TRUE(std::isnan(quantile({}, 0.5)));
}

TEST(FirstIndexReachingFromThereOn, SkipsAnEarlyLuckyScore) {
  EXPECT_EQ(firstIndexReachingFromThereOn({0.5, 0.9, 0.95}, 0.9), 1u);
  EXPECT_EQ(firstIndexReachingFromThereOn({0.95, 0.8, 0.92, 0.97}, 0.9), 2u);  // not 0
  EXPECT_EQ(firstIndexReachingFromThereOn({0.95, 0.97}, 0.95), 0u);            // equal reaches
  EXPECT_EQ(firstIndexReachingFromThereOn({0.99, 0.8}, 0.9), 2u);              // the last is below
  EXPECT_EQ(firstIndexReachingFromThereOn({}, 0.9), 0u);
}

TEST(MetricSummary, ByHand) {
  const MetricSummary s = summarize({
      found(5, 5, 5, 10, false),   // every criterion met
      found(8, 30, 20, 5, false),  // ADD-S < 10 mm, but ADD 30 mm and 20 degrees
      found(9, 40, 3, 15, true),   // symmetric: ADD(-S) is ADD-S, 9 mm
      missing(),                   // infinite errors
  });
  EXPECT_EQ(s.targets, 4u);
  EXPECT_EQ(s.found, 3u);
  EXPECT_DOUBLE_EQ(s.adds_auc, (0.95 + 0.92 + 0.91 + 0) / 4);
  EXPECT_DOUBLE_EQ(s.adds_success, 3.0 / 4);
  EXPECT_DOUBLE_EQ(s.add_or_adds_success, 2.0 / 4);
  EXPECT_DOUBLE_EQ(s.rt_success, 2.0 / 4);
  EXPECT_DOUBLE_EQ(s.median_adds_mm, 8.5);
  EXPECT_DOUBLE_EQ(s.median_rotation_deg, 12.5);
  EXPECT_DOUBLE_EQ(s.median_translation_mm, 12.5);
}

TEST(MetricSummary, MssdSuccessAndRecall) {
  TargetErrors close = found(5, 5, 5, 10, false), turned = close;
  close.mssd_mm = 8;    // below 0.1 to 0.5 of the 100 mm diameter: 9 of the 10 thresholds
  turned.mssd_mm = 32;  // below 0.35 to 0.5: 4 of them
  const MetricSummary s = summarize({close, turned, missing()});
  EXPECT_DOUBLE_EQ(s.mssd_success, 1.0 / 3);
  EXPECT_DOUBLE_EQ(s.mssd_recall, (0.9 + 0.4 + 0) / 3);
  close.mssd_mm = 10;  // bounds are strict
  EXPECT_FALSE(close.mssdSuccess());
  EXPECT_DOUBLE_EQ(close.mssdRecall(), 0.8);
  EXPECT_TRUE(std::isnan(summarize({}).mssd_recall));
}

TEST(MetricSummary, SuccessBoundsAreStrict) {
  const TargetErrors at_bounds = found(10, 10, 10, 20, false);
  EXPECT_FALSE(at_bounds.addsSuccess());
  EXPECT_FALSE(at_bounds.addOrAddsSuccess());
  EXPECT_FALSE(at_bounds.rtSuccess());
  EXPECT_TRUE(found(9.99, 9.99, 9.99, 19.99, false).rtSuccess());
  EXPECT_FALSE(missing().addsSuccess());
}

TEST(MetricSummary, EmptyIsNaN) {
  const MetricSummary s = summarize({});
  EXPECT_EQ(s.targets, 0u);
  EXPECT_TRUE(std::isnan(s.adds_auc));
  EXPECT_TRUE(std::isnan(s.rt_success));
}

}  // namespace
}  // namespace stocs
