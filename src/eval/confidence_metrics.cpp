#include "stocs/eval/confidence_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stocs {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double ratio(int numerator, int denominator) {
  return denominator > 0 ? static_cast<double>(numerator) / denominator : kNaN;
}

/// Equal-width bins over [0, 1] of the poses' scores; empty when a score lies outside [0, 1].
std::vector<ReliabilityBin> reliabilityBins(const std::vector<ScoredTarget>& targets, int bins) {
  std::vector<ReliabilityBin> table(bins);
  std::vector<int> correct(bins, 0);
  std::vector<double> sums(bins, 0);
  for (int b = 0; b < bins; ++b)
    table[b] = {static_cast<double>(b) / bins, static_cast<double>(b + 1) / bins};
  for (const ScoredTarget& t : targets) {
    if (!t.posed) continue;
    if (!(t.score >= 0 && t.score <= 1)) return {};
    const int b = std::min(bins - 1, static_cast<int>(t.score * bins));
    ++table[b].count;
    sums[b] += t.score;
    correct[b] += t.correct;
  }
  for (int b = 0; b < bins; ++b) {
    table[b].mean_score = table[b].count ? sums[b] / table[b].count : kNaN;
    table[b].share_correct = ratio(correct[b], table[b].count);
  }
  return table;
}

/// Pose-weighted mean gap between the mean score and the share correct of each bin.
double calibrationError(const std::vector<ReliabilityBin>& bins, int poses) {
  if (bins.empty() || poses == 0) return kNaN;
  double error = 0;
  for (const ReliabilityBin& b : bins) {
    if (b.count) error += b.count * std::abs(b.mean_score - b.share_correct);
  }
  return error / poses;
}

}  // namespace

double rocAuc(std::vector<double> positives, std::vector<double> negatives) {
  if (positives.empty() || negatives.empty()) return kNaN;
  std::sort(negatives.begin(), negatives.end());
  double wins = 0;
  for (double p : positives) {
    const auto below = std::lower_bound(negatives.begin(), negatives.end(), p);
    const auto above = std::upper_bound(below, negatives.end(), p);
    wins += (below - negatives.begin()) + 0.5 * (above - below);
  }
  return wins / (static_cast<double>(positives.size()) * negatives.size());
}

ConfidenceMetrics confidenceMetrics(const std::vector<ScoredTarget>& targets, double threshold,
                                    int bins) {
  ConfidenceMetrics m;
  m.threshold = threshold;
  std::vector<double> positives, negatives;
  int kept = 0, kept_correct = 0, absent_kept = 0;
  for (const ScoredTarget& t : targets) {
    const bool correct = t.posed && t.correct && !t.absent;
    const double score = t.posed ? t.score : -std::numeric_limits<double>::infinity();
    (correct ? positives : negatives).push_back(score);
    const bool above = t.posed && t.score >= threshold;
    ++m.targets;
    m.absent += t.absent;
    m.poses += t.posed;
    m.correct += correct;
    kept += above;
    kept_correct += above && correct;
    absent_kept += above && t.absent;
  }
  m.roc_auc = rocAuc(positives, negatives);
  m.reliability = reliabilityBins(targets, bins);
  m.ece = calibrationError(m.reliability, m.poses);
  m.precision = ratio(kept_correct, kept);
  m.recall = ratio(kept_correct, m.targets - m.absent);
  m.absent_posed = ratio(absent_kept, m.absent);
  m.correct_rejected = ratio(m.correct - kept_correct, m.correct);
  return m;
}

}  // namespace stocs
