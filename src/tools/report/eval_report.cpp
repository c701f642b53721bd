#include "eval_report.h"

namespace stocs::tools {

std::vector<Cell> metricHeader() {
  return {{"targets", "targets"},
          {"found", "found"},
          {"ADD-S AUC", "adds_auc"},
          {"ADD-S < 0.1d", "adds_success"},
          {"ADD(-S) < 0.1d", "add_or_adds_success"},
          {"MSSD < 0.1d", "mssd_success"},
          {"MSSD AR", "mssd_recall"},
          {"< 2 cm, 10°", "rt_success"},
          {"ADD-S median (mm)", "median_adds_mm"},
          {"rot. median (°)", "median_rotation_deg"},
          {"trans. median (cm)", "median_translation_cm"}};
}

std::vector<Cell> metricCells(const MetricSummary& m) {
  return {textCell(std::to_string(m.targets)),
          textCell(std::to_string(m.found)),
          percentCell(m.adds_auc),
          percentCell(m.adds_success),
          percentCell(m.add_or_adds_success),
          percentCell(m.mssd_success),
          percentCell(m.mssd_recall),
          percentCell(m.rt_success),
          numberCell(m.median_adds_mm, 1),
          numberCell(m.median_rotation_deg, 1),
          numberCell(m.median_translation_mm / 10, 2)};
}

std::string metricLegend() {
  return "ADD-S AUC: area under the ADD-S accuracy-threshold curve from 0 to 10 cm. "
         "ADD-S < 0.1d: ADD-S (closest model point) below 10% of the object diameter; "
         "ADD(-S): ADD-S for objects models_info.json marks symmetric, ADD otherwise. "
         "MSSD: BOP's maximum symmetry-aware surface distance, the largest distance between "
         "corresponding model points for the symmetric ground-truth pose (models_info.json) "
         "that makes it smallest; MSSD AR: the share below 0.05, 0.1, ..., 0.5 of the diameter, "
         "averaged over the ten thresholds (BOP's AR_MSSD). "
         "< 2 cm, 10°: translation error below 2 cm and mean roll, pitch, yaw error below 10 "
         "degrees (nearest symmetric pose). Medians over all targets. A target is one object in "
         "one image, compared with its nearest ground-truth instance; a missing estimate counts "
         "as a failure with infinite errors.\n";
}

std::string targetsCsv(const std::vector<std::string>& label_names,
                       const std::vector<LabelledTarget>& rows) {
  std::vector<Cell> header;
  for (const std::string& name : label_names) header.push_back(textCell(name));
  for (const char* name :
       {"scene_id", "im_id", "obj_id", "found", "score", "gt_index", "diameter_mm", "symmetric",
        "add_mm", "adds_mm", "add_or_adds_mm", "mssd_mm", "rotation_deg", "translation_cm",
        "adds_success", "add_or_adds_success", "mssd_success", "rt_success", "seconds"}) {
    header.push_back(textCell(name));
  }
  ReportTable table(header);
  for (const LabelledTarget& row : rows) {
    const TargetResult& r = row.result;
    const TargetErrors& e = r.errors;
    std::vector<Cell> cells;
    for (const std::string& label : row.labels) cells.push_back(textCell(label));
    for (int v : {r.target.scene_id, r.target.im_id, r.target.obj_id, static_cast<int>(e.found)}) {
      cells.push_back(textCell(std::to_string(v)));
    }
    cells.push_back(numberCell(r.score, 6));
    cells.push_back(textCell(std::to_string(r.gt_index)));
    cells.push_back(numberCell(e.diameter_mm, 3));
    cells.push_back(textCell(std::to_string(static_cast<int>(e.symmetric))));
    for (double v :
         {e.add_mm, e.adds_mm, e.addOrAddsMm(), e.mssd_mm, e.rotation_deg, e.translation_mm / 10}) {
      cells.push_back(numberCell(v, 3));
    }
    for (bool ok : {e.addsSuccess(), e.addOrAddsSuccess(), e.mssdSuccess(), e.rtSuccess()}) {
      cells.push_back(textCell(ok ? "1" : "0"));
    }
    cells.push_back(numberCell(row.seconds, 4));
    table.add(cells);
  }
  return table.csv();
}

std::string datasetName(const std::filesystem::path& folder) {
  const std::filesystem::path p = folder.lexically_normal();
  return (p.has_filename() ? p : p.parent_path()).filename().string();
}

std::vector<TargetErrors> errorsOf(const std::vector<TargetResult>& targets) {
  std::vector<TargetErrors> errors;
  for (const TargetResult& t : targets) errors.push_back(t.errors);
  return errors;
}

}  // namespace stocs::tools
