#include "stocs/eval/logistic_regression.h"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "stocs/eval/confidence_metrics.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

double sigmoid(double z) {
  return 1.0 / (1.0 + std::exp(-z));
}

/// Mean log loss plus the penalty, for coefficients [intercept; weights] on `x` (with a ones
/// column first).
double objective(const Eigen::MatrixXd& x, const Eigen::VectorXd& y, const Eigen::VectorXd& beta,
                 double l2) {
  const Eigen::VectorXd z = x * beta;
  double loss = 0;
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    // log(1 + e^z) - y z, computed without overflow
    loss += std::max(z[i], 0.0) + std::log1p(std::exp(-std::abs(z[i]))) - y[i] * z[i];
  }
  return loss / static_cast<double>(z.size()) + 0.5 * l2 * beta.tail(beta.size() - 1).squaredNorm();
}

}  // namespace

double LogisticModel::probability(const Eigen::VectorXd& x) const {
  return sigmoid(intercept + weights.dot(x));
}

LogisticModel fitLogistic(const Eigen::MatrixXd& features, const Eigen::VectorXd& labels,
                          double l2) {
  const Eigen::Index n = features.rows(), d = features.cols() + 1;
  if (n == 0 || labels.size() != n) {
    throw InputError(fmt::format("logistic fit: {} samples and {} labels", n, labels.size()));
  }
  Eigen::MatrixXd x(n, d);
  x << Eigen::VectorXd::Ones(n), features;
  Eigen::MatrixXd penalty = Eigen::MatrixXd::Identity(d, d) * l2;
  penalty(0, 0) = 0;
  Eigen::VectorXd beta = Eigen::VectorXd::Zero(d);
  double current = objective(x, labels, beta, l2);
  for (int iteration = 0; iteration < 100; ++iteration) {
    const Eigen::VectorXd p = (x * beta).unaryExpr(&sigmoid);
    const Eigen::VectorXd w = p.array() * (1 - p.array());
    const Eigen::VectorXd gradient = x.transpose() * (p - labels) / n + penalty * beta;
    const Eigen::MatrixXd hessian =
        x.transpose() * w.asDiagonal() * x / n + penalty +
        1e-12 * Eigen::MatrixXd::Identity(d, d);  // the intercept alone may be unconstrained
    const Eigen::VectorXd step = hessian.ldlt().solve(gradient);
    // Newton's step, halved while it does not lower the objective (far from the optimum).
    double scale = 1, next = current;
    for (; scale > 1e-6; scale /= 2) {
      next = objective(x, labels, beta - scale * step, l2);
      if (next <= current) break;
    }
    if (scale <= 1e-6) break;
    beta -= scale * step;
    const bool converged = current - next < 1e-12;
    current = next;
    if (converged) break;
  }
  return {beta[0], beta.tail(d - 1)};
}

ProbabilityFit probabilityFit(const std::vector<double>& probabilities,
                              const std::vector<int>& labels) {
  const size_t n = probabilities.size();
  if (n == 0 || labels.size() != n) {
    throw InputError(
        fmt::format("probability fit: {} probabilities and {} labels", n, labels.size()));
  }
  ProbabilityFit fit;
  std::vector<ScoredTarget> poses;
  for (size_t i = 0; i < n; ++i) {
    const double p = std::clamp(probabilities[i], 1e-12, 1 - 1e-12);
    fit.log_loss -= labels[i] ? std::log(p) : std::log(1 - p);
    poses.push_back({true, probabilities[i], labels[i] != 0, false});
  }
  fit.log_loss /= static_cast<double>(n);
  const ConfidenceMetrics metrics = confidenceMetrics(poses, 0.5);
  fit.calibration_error = metrics.ece;
  fit.roc_auc = metrics.roc_auc;
  return fit;
}

}  // namespace stocs
