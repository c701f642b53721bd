#include "object_runs.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <fstream>
#include <optional>
#include <sstream>

#include "report_table.h"
#include "stocs/util/error.h"

namespace stocs::tools {
namespace {

constexpr int kFixedColumns = 8;                                          // scene_id to hypotheses
constexpr int kColumns = kFixedColumns + ConfidenceEvidence::kCount + 1;  // then the covariance

/// The row's numbers and its covariance (the last column: 36 numbers, row by row, separated by
/// blanks), or nothing unless there are exactly kColumns numbers before it.
std::optional<std::pair<std::vector<double>, Eigen::Matrix<double, 6, 6>>> parseRow(
    const std::string& line) {
  std::vector<double> values;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) {
    std::stringstream cs(cell);
    if (static_cast<int>(values.size()) == kColumns) {
      Eigen::Matrix<double, 6, 6> covariance;
      for (int i = 0; i < 36; ++i) {
        if (!(cs >> covariance.data()[i])) return std::nullopt;
      }
      if (!(cs >> std::ws).eof() || std::getline(ss, cell, ',')) return std::nullopt;
      return std::make_pair(values, covariance);
    }
    double v = 0;
    if (!(cs >> v) || !(cs >> std::ws).eof()) return std::nullopt;
    values.push_back(v);
  }
  return std::nullopt;
}

}  // namespace

void writeObjectRuns(const std::filesystem::path& file, const std::vector<ObjectRun>& runs) {
  std::string text = fmt::format(
      "scene_id,im_id,obj_id,found,seconds,cpu_seconds,segment_points,hypotheses,{},confidence,"
      "covariance\n",
      fmt::join(ConfidenceEvidence::names(), ","));
  for (const ObjectRun& r : runs) {
    text +=
        fmt::format("{},{},{},{},{:.6f},{:.6f},{},{},{:.5f},{:.5f},{:.9g}\n", r.target.scene_id,
                    r.target.im_id, r.target.obj_id, r.found ? 1 : 0, r.seconds, r.cpu_seconds,
                    r.segment_points, r.hypotheses, fmt::join(r.evidence.features(), ","),
                    r.confidence, fmt::join(r.covariance.data(), r.covariance.data() + 36, " "));
  }
  writeTextFile(file, text);
}

std::vector<ObjectRun> readObjectRuns(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{}: cannot open", file.string()));
  std::vector<ObjectRun> runs;
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    if (line_no == 1 || line.empty()) continue;  // header
    const auto row = parseRow(line);
    if (!row) {
      throw InputError(
          fmt::format("{}:{}: expected {} comma-separated numbers and a covariance of 36",
                      file.string(), line_no, kColumns));
    }
    const std::vector<double>& x = row->first;
    ObjectRun r;
    r.covariance = row->second;
    r.target = {static_cast<int>(x[0]), static_cast<int>(x[1]), static_cast<int>(x[2])};
    r.found = x[3] != 0;
    r.seconds = x[4];
    r.cpu_seconds = x[5];
    r.segment_points = static_cast<size_t>(x[6]);
    r.hypotheses = static_cast<long>(x[7]);
    r.evidence = ConfidenceEvidence::fromFeatures(
        Eigen::Map<const Eigen::Matrix<double, ConfidenceEvidence::kCount, 1>>(&x[kFixedColumns]));
    r.confidence = static_cast<float>(x[kColumns - 1]);
    runs.push_back(r);
  }
  return runs;
}

}  // namespace stocs::tools
