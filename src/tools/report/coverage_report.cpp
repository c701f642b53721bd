#include "coverage_report.h"

#include <fmt/format.h>

#include "object_runs.h"
#include "stocs/eval/covariance_coverage.h"

namespace stocs::tools {

std::string coverageNote(const std::string& results_name, const std::filesystem::path& per_object,
                         const std::vector<TargetResult>& targets, const BopDataset& dataset) {
  std::map<Target, PoseCovarianceMatrix> covariances;
  for (const ObjectRun& run : readObjectRuns(per_object)) {
    if (run.found) covariances[run.target] = run.covariance;
  }
  const EllipsoidCoverage c = correctPoseCoverage(targets, covariances, dataset.modelsInfo());
  if (c.poses == 0) {
    return fmt::format("- {}: covariance: no correct pose with a covariance in {}.\n", results_name,
                       per_object.string());
  }
  return fmt::format(
      "- {}: covariance: of the true errors of {} correct poses, {:.1f}% lie inside the 50% "
      "confidence ellipsoid and {:.1f}% inside the 90% one.\n",
      results_name, c.poses, 100 * c.within50, 100 * c.within90);
}

}  // namespace stocs::tools
