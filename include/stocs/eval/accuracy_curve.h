#pragma once
// The accuracy-threshold curve of pose errors and the area under it, the YCB-Video protocol of
// PoseCNN (Xiang et al. 2018) used by the paper's Table 2 with ADD-S and a 10 cm limit.
//
// accuracy(x) = fraction of errors below x. The area is normalised by the limit L:
//   AUC = (1 / L) * integral_0^L accuracy(x) dx = mean over errors e of max(0, 1 - e / L),
// exactly (each error contributes the length of [e, L]). A missing estimate has an infinite error
// and contributes 0. PoseCNN's toolbox (`VOCap`) integrates the curve at the right end of each step
// instead, which adds max_e(e <= L) / (L * n) for n errors: nothing on YCB-Video's thousands of
// targets, but it would score a single target with any error below L as 100%.

#include <vector>

namespace stocs {

/// Fraction of `errors` strictly below `threshold` (0 for an empty list).
double accuracyBelow(const std::vector<double>& errors, double threshold);

/// Area under the accuracy-threshold curve up to `limit`, in [0, 1]; NaN for an empty list. Throws
/// InputError unless `limit` > 0.
double accuracyCurveArea(const std::vector<double>& errors, double limit);

}  // namespace stocs
