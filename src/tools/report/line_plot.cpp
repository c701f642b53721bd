#include "line_plot.h"

#include <fmt/format.h>

#include <unistd.h>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "child_process.h"
#include "report_table.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/util/error.h"

namespace stocs::tools {
namespace {

/// A double-quoted gnuplot string.
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string range(double lo, double hi) {
  const auto bound = [](double v) {
    return std::isnan(v) ? std::string("*") : fmt::format("{}", v);
  };
  return fmt::format("[{}:{}]", bound(lo), bound(hi));
}

}  // namespace

std::string findGnuplot() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::filesystem::path candidate = std::filesystem::path(dir) / "gnuplot";
    if (!dir.empty() && access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return "";
}

void renderPlot(const LinePlot& plot, const std::filesystem::path& png) {
  std::filesystem::path data = png, script = png, log = png;
  data.replace_extension(".dat");
  script.replace_extension(".gp");
  log.replace_extension(".log");
  std::string rows, plots;
  int index = 0;
  for (const PlotSeries& s : plot.series) {
    if (s.points.empty()) continue;
    // Blocks separated by two blank lines are gnuplot's data sets, selected by `index`.
    for (const Eigen::Vector2d& p : s.points) rows += fmt::format("{:.9g} {:.9g}\n", p.x(), p.y());
    rows += "\n\n";
    plots += fmt::format("{}{} index {} using 1:2 with {} lw 2 title {}", index ? ", \\\n  " : "",
                         index ? "''" : quoted(data.filename().string()), index,
                         plot.markers ? "linespoints pt 7 ps 0.8" : "lines", quoted(s.name));
    ++index;
  }
  std::string gp = fmt::format(
      "# Redraw with: gnuplot {}\n"
      "set terminal pngcairo size 900,600 font 'DejaVu Sans,12' noenhanced\n"
      "set output {}\n"
      "set title {}\nset xlabel {}\nset ylabel {}\n"
      "set xrange {}\nset yrange {}\n"
      "set grid\nset key outside right top box\n",
      script.filename().string(), quoted(png.filename().string()), quoted(plot.title),
      quoted(plot.x_label), quoted(plot.y_label), range(plot.x_min, plot.x_max),
      range(plot.y_min, plot.y_max));
  if (plot.log_x) gp += "set logscale x\n";
  gp += index ? "plot " + plots + "\n"
              : "set label 1 'no data' at graph 0.5, 0.5 center\nplot NaN notitle\n";
  writeTextFile(data, rows);
  writeTextFile(script, gp);
  std::filesystem::remove(log);
  std::filesystem::remove(png);
  const std::string gnuplot = findGnuplot();
  if (gnuplot.empty()) throw InputError("gnuplot is not installed (Debian package gnuplot-nox)");
  // gnuplot resolves the data file relative to its working folder: run it in the plot's folder.
  const ChildOutcome outcome =
      runChild({"/bin/sh", "-c", "cd \"$1\" && exec \"$2\" \"$3\"", "sh",
                png.parent_path().empty() ? "." : png.parent_path().string(), gnuplot,
                script.filename().string()},
               log);
  if (!outcome.ok() || !std::filesystem::exists(png)) {
    throw InputError(fmt::format("gnuplot failed on {} ({}): {}", script.string(),
                                 outcome.describe(), readTextFile(log)));
  }
  std::filesystem::remove(log);
}

}  // namespace stocs::tools
