#pragma once
// The confidence columns `stocs eval` and `stocs bench` report for each method (from the BOP score
// column): ROC AUC, calibration error, the figures at a score threshold, the reliability table and
// its plot (see confidence_metrics.h).

#include <string>
#include <vector>

#include "line_plot.h"
#include "report_table.h"
#include "stocs/eval/confidence_metrics.h"
#include "stocs/eval/dataset_evaluation.h"

namespace stocs::tools {

/// Each target as the confidence metrics see it: posed, its score, correct (ADD-S below 10% of
/// the diameter), absent.
std::vector<ScoredTarget> scoredTargets(const std::vector<TargetResult>& targets);

/// Header and cells: absent targets, ROC AUC, ECE ("n/a" for scores outside [0, 1], "-" without
/// poses), and at the threshold precision, recall, absent objects posed and correct poses
/// rejected.
std::vector<Cell> confidenceHeader();
std::vector<Cell> confidenceCells(const ConfidenceMetrics& m);

/// Markdown lines that define the columns of confidenceHeader() at `threshold`.
std::string confidenceLegend(double threshold);

/// Markdown table of the reliability bins: range, poses, mean score, share correct.
std::string reliabilityMarkdown(const ConfidenceMetrics& m);

/// The share correct against the mean score of each non-empty bin, one series per name, with
/// the diagonal of a calibrated score.
LinePlot reliabilityPlot(const std::string& title,
                         const std::vector<std::pair<std::string, ConfidenceMetrics>>& series);

}  // namespace stocs::tools
