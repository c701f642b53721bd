#include "stocs/eval/accuracy_curve.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stocs/util/error.h"

namespace stocs {

double accuracyBelow(const std::vector<double>& errors, double threshold) {
  if (errors.empty()) return 0;
  const auto below =
      std::count_if(errors.begin(), errors.end(), [&](double e) { return e < threshold; });
  return static_cast<double>(below) / errors.size();
}

double accuracyCurveArea(const std::vector<double>& errors, double limit) {
  if (!(limit > 0)) throw InputError("accuracy curve limit must be positive");
  if (errors.empty()) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0;
  for (double e : errors) sum += std::max(0.0, 1.0 - e / limit);
  return sum / errors.size();
}

}  // namespace stocs
