#include "stocs/eval/metric_summary.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stocs/eval/accuracy_curve.h"

namespace stocs {

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const double position = q * (values.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(position));
  const size_t hi = std::min(lo + 1, values.size() - 1);
  const double f = position - lo;
  if (f == 0) return values[lo];
  if (std::isinf(values[hi])) return values[hi];
  return values[lo] + (values[hi] - values[lo]) * f;
}

size_t firstIndexReachingFromThereOn(const std::vector<double>& scores, double target) {
  size_t first = scores.size();
  while (first > 0 && scores[first - 1] >= target) --first;
  return first;
}

MetricSummary summarize(const std::vector<TargetErrors>& errors) {
  MetricSummary s;
  s.targets = errors.size();
  if (errors.empty()) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    s.adds_auc = s.adds_success = s.add_or_adds_success = s.rt_success = nan;
    s.mssd_success = s.mssd_recall = nan;
    s.median_adds_mm = s.median_rotation_deg = s.median_translation_mm = nan;
    return s;
  }
  std::vector<double> adds, rotation, translation;
  size_t adds_ok = 0, add_ok = 0, mssd_ok = 0, rt_ok = 0;
  double mssd_recall = 0;
  for (const TargetErrors& e : errors) {
    s.found += e.found;
    adds_ok += e.addsSuccess();
    add_ok += e.addOrAddsSuccess();
    mssd_ok += e.mssdSuccess();
    mssd_recall += e.mssdRecall();
    rt_ok += e.rtSuccess();
    adds.push_back(e.adds_mm);
    rotation.push_back(e.rotation_deg);
    translation.push_back(e.translation_mm);
  }
  const double n = static_cast<double>(errors.size());
  s.adds_auc = accuracyCurveArea(adds, kAddsCurveLimitMm);
  s.adds_success = adds_ok / n;
  s.add_or_adds_success = add_ok / n;
  s.mssd_success = mssd_ok / n;
  s.mssd_recall = mssd_recall / n;
  s.rt_success = rt_ok / n;
  s.median_adds_mm = quantile(adds, 0.5);
  s.median_rotation_deg = quantile(rotation, 0.5);
  s.median_translation_mm = quantile(translation, 0.5);
  return s;
}

}  // namespace stocs
