#include "stocs/eval/logistic_regression.h"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

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
  ProbabilityFit fit;
  if (n == 0 || labels.size() != n) {
    throw InputError(
        fmt::format("probability fit: {} probabilities and {} labels", n, labels.size()));
  }
  constexpr int kBins = 10;
  std::vector<double> bin_p(kBins, 0), bin_y(kBins, 0), bin_n(kBins, 0);
  for (size_t i = 0; i < n; ++i) {
    const double p = std::clamp(probabilities[i], 1e-12, 1 - 1e-12);
    fit.log_loss -= labels[i] ? std::log(p) : std::log(1 - p);
    const int b = std::min(kBins - 1, static_cast<int>(probabilities[i] * kBins));
    bin_p[b] += probabilities[i];
    bin_y[b] += labels[i];
    bin_n[b] += 1;
  }
  fit.log_loss /= static_cast<double>(n);
  for (int b = 0; b < kBins; ++b) fit.calibration_error += std::abs(bin_p[b] - bin_y[b]) / n;
  // ROC AUC by ranks (Mann-Whitney U), ties sharing their mean rank.
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return probabilities[a] < probabilities[b]; });
  double positive_ranks = 0, positives = 0;
  for (size_t i = 0; i < n;) {
    size_t j = i;
    while (j < n && probabilities[order[j]] == probabilities[order[i]]) ++j;
    const double rank = (static_cast<double>(i + j) + 1) / 2;  // mean of ranks i+1 .. j
    for (size_t k = i; k < j; ++k) {
      if (labels[order[k]]) positive_ranks += rank, positives += 1;
    }
    i = j;
  }
  const double negatives = static_cast<double>(n) - positives;
  fit.roc_auc = positives == 0 || negatives == 0
                    ? std::numeric_limits<double>::quiet_NaN()
                    : (positive_ranks - positives * (positives + 1) / 2) / (positives * negatives);
  return fit;
}

}  // namespace stocs
