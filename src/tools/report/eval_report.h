#pragma once
// The columns `stocs eval` and `stocs bench` report metrics in: a summary of targets, and one row
// per target.

#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "report_table.h"
#include "stocs/eval/dataset_evaluation.h"
#include "stocs/eval/metric_summary.h"

namespace stocs::tools {

/// Header and cells of a MetricSummary: targets, found, ADD-S AUC, the ADD-S, ADD(-S) and MSSD
/// success rates, the MSSD recall, the APC success rate and the median ADD-S, rotation and
/// translation errors.
std::vector<Cell> metricHeader();
std::vector<Cell> metricCells(const MetricSummary& summary);

/// Markdown lines that define the columns of metricHeader().
std::string metricLegend();

struct LabelledTarget {
  std::vector<std::string> labels;
  TargetResult result;
  double seconds = std::numeric_limits<double>::quiet_NaN();  ///< time for the object, if known
};

/// One CSV row per target: the labels, the target, every error and success, and the time.
std::string targetsCsv(const std::vector<std::string>& label_names,
                       const std::vector<LabelledTarget>& rows);

/// The name a dataset is reported under: its folder's name (a trailing separator ignored).
std::string datasetName(const std::filesystem::path& folder);

/// Errors of the given targets, for summarize().
std::vector<TargetErrors> errorsOf(const std::vector<TargetResult>& targets);

}  // namespace stocs::tools
