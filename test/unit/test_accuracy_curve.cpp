// The ADD-S accuracy-threshold curve and its area, on hand-computed cases.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "stocs/eval/accuracy_curve.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

const double kInf = std::numeric_limits<double>::infinity();

TEST(AccuracyCurve, AccuracyCountsErrorsStrictlyBelow) {
  const std::vector<double> errors = {10, 50, kInf};
  EXPECT_DOUBLE_EQ(accuracyBelow(errors, 10), 0.0);
  EXPECT_DOUBLE_EQ(accuracyBelow(errors, 50), 1.0 / 3);
  EXPECT_DOUBLE_EQ(accuracyBelow(errors, 50.1), 2.0 / 3);
  EXPECT_DOUBLE_EQ(accuracyBelow({}, 50), 0.0);
}

TEST(AccuracyCurve, AreaByHand) {
  // Each error contributes the share of [0, 100] it is below: 1, 0.5, 0 (missing).
  EXPECT_DOUBLE_EQ(accuracyCurveArea({0, 50, kInf}, 100), 0.5);
  // 0.75 and 0 (beyond the limit).
  EXPECT_DOUBLE_EQ(accuracyCurveArea({25, 150}, 100), 0.375);
  // One target at 5 cm covers half the curve (PoseCNN's VOCap would report 100%).
  EXPECT_DOUBLE_EQ(accuracyCurveArea({50}, 100), 0.5);
  EXPECT_TRUE(std::isnan(accuracyCurveArea({}, 100)));
  EXPECT_THROW(accuracyCurveArea({1}, 0), InputError);
}

TEST(AccuracyCurve, AreaIsTheIntegralOfTheCurve) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 140);
  std::vector<double> errors;
  for (int i = 0; i < 37; ++i) errors.push_back(u(rng));
  errors.push_back(kInf);
  const int steps = 200000;
  double integral = 0;
  for (int i = 0; i < steps; ++i) integral += accuracyBelow(errors, (i + 0.5) * 100.0 / steps);
  EXPECT_NEAR(accuracyCurveArea(errors, 100), integral / steps, 1e-4);
}

}  // namespace
}  // namespace stocs
