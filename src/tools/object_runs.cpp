#include "object_runs.h"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

#include "report_table.h"
#include "stocs/util/error.h"

namespace stocs::tools {
namespace {

/// The 36 numbers of a covariance, row by row (symmetric, so the order is either), and nothing
/// more.
bool readCovariance(std::stringstream& ss, Eigen::Matrix<double, 6, 6>& covariance) {
  for (int i = 0; i < 36; ++i) {
    if (!(ss >> covariance.data()[i])) return false;
  }
  std::string rest;
  return !(ss >> rest);
}

}  // namespace

void writeObjectRuns(const std::filesystem::path& file, const std::vector<ObjectRun>& runs) {
  std::string text =
      "scene_id,im_id,obj_id,found,seconds,cpu_seconds,segment_points,hypotheses,covariance\n";
  for (const ObjectRun& r : runs) {
    text +=
        fmt::format("{},{},{},{},{:.6f},{:.6f},{},{},{:.9g}\n", r.target.scene_id, r.target.im_id,
                    r.target.obj_id, r.found ? 1 : 0, r.seconds, r.cpu_seconds, r.segment_points,
                    r.hypotheses, fmt::join(r.covariance.data(), r.covariance.data() + 36, " "));
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
    std::stringstream ss(line);
    ObjectRun r;
    int found = 0;
    char c[8];
    if (!(ss >> r.target.scene_id >> c[0] >> r.target.im_id >> c[1] >> r.target.obj_id >> c[2] >>
          found >> c[3] >> r.seconds >> c[4] >> r.cpu_seconds >> c[5] >> r.segment_points >> c[6] >>
          r.hypotheses >> c[7]) ||
        std::string(c, 8) != ",,,,,,,," || !readCovariance(ss, r.covariance)) {
      throw InputError(
          fmt::format("{}:{}: expected 8 comma-separated numbers and a covariance of 36",
                      file.string(), line_no));
    }
    r.found = found != 0;
    runs.push_back(r);
  }
  return runs;
}

}  // namespace stocs::tools
