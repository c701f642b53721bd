#pragma once
// The figures a set of targets is summarised by (per object, per dataset, overall): success rates,
// the area under the ADD-S accuracy-threshold curve up to 10 cm, BOP's MSSD recall, and median
// errors. Missing estimates count in every figure as infinite errors.

#include <cstddef>
#include <vector>

#include "stocs/eval/object_metrics.h"

namespace stocs {

/// Upper end of the ADD-S accuracy-threshold curve, mm (PoseCNN's 0.1 m).
constexpr double kAddsCurveLimitMm = 100;

struct MetricSummary {
  size_t targets = 0;
  size_t found = 0;
  double adds_auc = 0;             ///< area under the ADD-S curve up to 10 cm, in [0, 1]
  double adds_success = 0;         ///< fraction with ADD-S < 10% of the diameter
  double add_or_adds_success = 0;  ///< fraction with ADD(-S) < 10% of the diameter
  double mssd_success = 0;         ///< fraction with MSSD < 10% of the diameter
  double mssd_recall = 0;          ///< BOP's MSSD recall averaged over 0.05..0.5 of the diameter
  double rt_success = 0;           ///< fraction with rotation < 10 deg and translation < 2 cm
  double median_adds_mm = 0;
  double median_rotation_deg = 0;
  double median_translation_mm = 0;
};

/// Summary of `errors`; every figure but the counts is NaN for an empty list.
MetricSummary summarize(const std::vector<TargetErrors>& errors);

/// The q-quantile (q in [0, 1]) with linear interpolation between order statistics (position
/// q * (n - 1), numpy's default): q = 0.5 is the usual median. Infinite values sort last; a
/// quantile that touches one is infinite. NaN for an empty list.
double quantile(std::vector<double> values, double q);

/// For a setting swept in increasing order with `scores` (e.g. ADD-S AUC at more and more bases):
/// the first index from which on every score is at least `target`, or scores.size() when the last
/// one is below it. A single lucky score early in a noisy sweep does not count.
size_t firstIndexReachingFromThereOn(const std::vector<double>& scores, double target);

}  // namespace stocs
