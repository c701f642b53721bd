#pragma once
// The covariance line of `stocs eval --per-object`: how many true errors of correct poses lie
// inside the estimates' 50% and 90% confidence ellipsoids (stocs/eval/covariance_coverage.h).

#include <filesystem>
#include <string>
#include <vector>

#include "stocs/eval/dataset_evaluation.h"
#include "stocs/io/bop_dataset.h"

namespace stocs::tools {

/// A markdown bullet naming `results_name` with the coverage of the covariances in `per_object`
/// (a `stocs estimate --per-object` file of the same run) over `targets`. Throws InputError for a
/// malformed file.
std::string coverageNote(const std::string& results_name, const std::filesystem::path& per_object,
                         const std::vector<TargetResult>& targets, const BopDataset& dataset);

}  // namespace stocs::tools
