// The confidence's logistic fit: it recovers known coefficients from data sampled from them, stays
// finite on separable data, and the fit measures (log loss, ROC AUC, calibration error) agree with
// hand-computed values.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "stocs/eval/logistic_regression.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

TEST(LogisticRegression, RecoversTheCoefficientsDataWasSampledFrom) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> feature(0, 1);
  const Eigen::Vector3d truth(4.0, -6.0, 1.5);
  const double intercept = -0.5;
  const int n = 20000;
  Eigen::MatrixXd x(n, 3);
  Eigen::VectorXd y(n);
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) x(i, k) = feature(rng);
    const double p = 1 / (1 + std::exp(-(intercept + truth.dot(x.row(i).transpose()))));
    y[i] = std::bernoulli_distribution(p)(rng);
  }
  const LogisticModel fit = fitLogistic(x, y, 0);
  EXPECT_NEAR(fit.intercept, intercept, 0.25);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(fit.weights[k], truth[k], 0.3) << "weight " << k;
}

TEST(LogisticRegression, SeparableDataStaysFiniteWithTheL2Term) {
  Eigen::MatrixXd x(4, 1);
  x << 0.1, 0.2, 0.8, 0.9;
  const Eigen::VectorXd y = (Eigen::VectorXd(4) << 0, 0, 1, 1).finished();
  const LogisticModel fit = fitLogistic(x, y, 1e-3);
  EXPECT_TRUE(std::isfinite(fit.intercept));
  EXPECT_TRUE(std::isfinite(fit.weights[0]));
  EXPECT_GT(fit.weights[0], 10);  // steep, as the data asks
  EXPECT_LT(fit.weights[0], 1000);
  EXPECT_LT(fit.probability(Eigen::VectorXd::Constant(1, 0.1)), 0.1);
  EXPECT_GT(fit.probability(Eigen::VectorXd::Constant(1, 0.9)), 0.9);
}

TEST(LogisticRegression, RefusesMismatchedSamples) {
  EXPECT_THROW(fitLogistic(Eigen::MatrixXd(3, 2), Eigen::VectorXd(2)), InputError);
  EXPECT_THROW(fitLogistic(Eigen::MatrixXd(0, 2), Eigen::VectorXd(0)), InputError);
  EXPECT_THROW(probabilityFit({0.5}, {}), InputError);
}

TEST(ProbabilityFit, MatchesHandComputedValues) {
  // Positives 0.9, 0.6 and 0.4; negatives 0.4 and 0.1. Pairs: (0.9, 0.6 beat both, 0.4 ties 0.4
  // and beats 0.1) = 5.5 of 6.
  const std::vector<double> p = {0.9, 0.6, 0.4, 0.4, 0.1};
  const std::vector<int> y = {1, 1, 1, 0, 0};
  const ProbabilityFit fit = probabilityFit(p, y);
  EXPECT_NEAR(fit.roc_auc, 5.5 / 6, 1e-12);
  const double loss =
      -(std::log(0.9) + std::log(0.6) + std::log(0.4) + std::log(0.6) + std::log(0.9)) / 5;
  EXPECT_NEAR(fit.log_loss, loss, 1e-12);
  // Bins, |sum of p - positives|: 0.9 -> 0.1; 0.6 -> 0.4; 0.4 and 0.4 -> |0.8 - 1|; 0.1 -> 0.1.
  EXPECT_NEAR(fit.calibration_error, (0.1 + 0.4 + 0.2 + 0.1) / 5, 1e-12);
  EXPECT_TRUE(std::isnan(probabilityFit({0.3, 0.7}, {1, 1}).roc_auc));
}

}  // namespace
}  // namespace stocs
