#pragma once
// Logistic regression for the pose confidence (`stocs calibrate`): Newton's method (iteratively
// reweighted least squares) on the mean log loss with an L2 penalty on the weights, which keeps
// the coefficients finite when the classes are separable. And how well probabilities fit labels.

#include <Eigen/Core>
#include <vector>

namespace stocs {

struct LogisticModel {
  double intercept = 0;
  Eigen::VectorXd weights;

  /// sigmoid(intercept + weights . x)
  double probability(const Eigen::VectorXd& x) const;
};

/// Fits P(label = 1 | x) to the rows of `features` (one sample per row) and `labels` (0 or 1),
/// minimising the mean log loss + l2 / 2 * |weights|^2 (the intercept is not penalised).
/// Throws InputError on mismatched sizes or no samples.
LogisticModel fitLogistic(const Eigen::MatrixXd& features, const Eigen::VectorXd& labels,
                          double l2 = 1e-3);

/// How well predicted probabilities fit 0/1 outcomes.
struct ProbabilityFit {
  double log_loss = 0;  ///< mean negative log likelihood
  /// Probability that a random positive gets a higher value than a random negative (ties count
  /// half); NaN without both classes.
  double roc_auc = 0;
  /// Expected calibration error: over 10 equal-width bins of probability, the sample-weighted mean
  /// |mean probability - share of positives|.
  double calibration_error = 0;
};

ProbabilityFit probabilityFit(const std::vector<double>& probabilities,
                              const std::vector<int>& labels);

}  // namespace stocs
