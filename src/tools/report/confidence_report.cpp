#include "confidence_report.h"

#include <fmt/format.h>

namespace stocs::tools {

std::vector<ScoredTarget> scoredTargets(const std::vector<TargetResult>& targets) {
  std::vector<ScoredTarget> scored;
  for (const TargetResult& t : targets) {
    scored.push_back(
        {t.errors.found, t.score, t.errors.found && t.errors.addsSuccess(), t.absent()});
  }
  return scored;
}

std::vector<Cell> confidenceHeader() {
  return {{"absent", "absent_targets"},
          {"score ROC AUC", "score_roc_auc"},
          {"ECE", "ece"},
          {"precision @t", "precision_at_t"},
          {"recall @t", "recall_at_t"},
          {"absent posed @t", "absent_posed_at_t"},
          {"correct rejected @t", "correct_rejected_at_t"}};
}

std::vector<Cell> confidenceCells(const ConfidenceMetrics& m) {
  return {textCell(std::to_string(m.absent)),
          numberCell(m.roc_auc, 3),
          m.reliability.empty() ? Cell{"n/a", ""} : numberCell(m.ece, 3),
          percentCell(m.precision),
          percentCell(m.recall),
          percentCell(m.absent_posed),
          percentCell(m.correct_rejected)};
}

std::string confidenceLegend(double threshold) {
  return fmt::format(
      "Confidence, from the results' score column: a pose is correct when its ADD-S is below 10% "
      "of the diameter; absent: targets whose object is not in the image (inst_count 0), where "
      "any pose is wrong. Score ROC AUC: probability that a correct pose scores above any other "
      "target (wrong poses, poses of absent objects; a target without a pose ranks lowest). ECE: "
      "expected calibration error of the poses over 10 equal-width score bins (n/a when a score "
      "lies outside [0, 1]). At t = {}: precision = correct poses with score >= t / poses with "
      "score >= t; recall = correct poses with score >= t / targets whose object is present; "
      "absent posed = absent targets with a pose of score >= t / absent targets; correct "
      "rejected = correct poses with score < t / correct poses.\n",
      threshold);
}

std::string reliabilityMarkdown(const ConfidenceMetrics& m) {
  if (m.reliability.empty()) return "No reliability table: a score lies outside [0, 1].\n";
  ReportTable table(
      {textCell("score"), textCell("poses"), textCell("mean score"), textCell("share correct")});
  for (const ReliabilityBin& b : m.reliability) {
    table.add({textCell(fmt::format("[{:.1f}, {:.1f}{}", b.lo, b.hi, b.hi >= 1 ? "]" : ")")),
               textCell(std::to_string(b.count)), numberCell(b.mean_score, 3),
               percentCell(b.share_correct)});
  }
  return table.markdown();
}

LinePlot reliabilityPlot(const std::string& title,
                         const std::vector<std::pair<std::string, ConfidenceMetrics>>& series) {
  LinePlot plot;
  plot.title = title;
  plot.x_label = "mean score of the bin";
  plot.y_label = "share of correct poses";
  plot.x_min = plot.y_min = 0;
  plot.x_max = plot.y_max = 1;
  plot.series.push_back({"calibrated", {{0, 0}, {1, 1}}});
  for (const auto& [name, m] : series) {
    PlotSeries s{name, {}};
    for (const ReliabilityBin& b : m.reliability) {
      if (b.count > 0) s.points.push_back({b.mean_score, b.share_correct});
    }
    plot.series.push_back(s);
  }
  return plot;
}

}  // namespace stocs::tools
