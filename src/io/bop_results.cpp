#include "stocs/io/bop_results.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "stocs/util/error.h"

namespace stocs {
namespace fs = std::filesystem;

void writeBopResults(const fs::path& file, const std::vector<BopResult>& results) {
  const fs::path tmp = file.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    if (!out) throw InputError(fmt::format("{}: cannot open for writing", tmp.string()));
    out << "scene_id,im_id,obj_id,score,R,t,time\n";
    for (const BopResult& r : results) {
      out << fmt::format("{},{},{},{:.6g},", r.scene_id, r.im_id, r.obj_id, r.score);
      for (int k = 0; k < 9; ++k) out << fmt::format("{}{:.9g}", k ? " " : "", r.R(k / 3, k % 3));
      out << ',';
      for (int k = 0; k < 3; ++k) out << fmt::format("{}{:.6f}", k ? " " : "", r.t_mm[k]);
      out << fmt::format(",{:.6f}\n", r.time);
    }
    if (!out) throw InputError(fmt::format("{}: write failed", tmp.string()));
  }
  std::error_code ec;
  fs::rename(tmp, file, ec);
  if (ec)
    throw InputError(fmt::format("{}: cannot rename into place: {}", file.string(), ec.message()));
}

std::vector<BopResult> readBopResults(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{}: cannot open", file.string()));
  std::vector<BopResult> results;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || (line_no == 1 && line.rfind("scene_id", 0) == 0)) continue;
    auto fail = [&](const std::string& why) {
      return InputError(fmt::format("{}:{}: {}", file.string(), line_no, why));
    };
    std::vector<std::string> cols;
    std::stringstream ss(line);
    for (std::string col; std::getline(ss, col, ',');) cols.push_back(col);
    if (cols.size() != 7)
      throw fail(fmt::format("expected 7 comma-separated columns, got {}", cols.size()));
    BopResult r;
    try {
      r.scene_id = std::stoi(cols[0]);
      r.im_id = std::stoi(cols[1]);
      r.obj_id = std::stoi(cols[2]);
      r.score = std::stod(cols[3]);
      r.time = std::stod(cols[6]);
    } catch (const std::exception&) {
      throw fail("scene_id, im_id, obj_id, score or time is not a number");
    }
    std::stringstream rs(cols[4]), ts(cols[5]);
    for (int k = 0; k < 9; ++k) {
      if (!(rs >> r.R(k / 3, k % 3))) throw fail("R must hold 9 numbers");
    }
    for (int k = 0; k < 3; ++k) {
      if (!(ts >> r.t_mm[k])) throw fail("t must hold 3 numbers");
    }
    if (!r.R.allFinite() || !r.t_mm.allFinite() || !std::isfinite(r.score))
      throw fail("non-finite value");
    results.push_back(r);
  }
  return results;
}

}  // namespace stocs
