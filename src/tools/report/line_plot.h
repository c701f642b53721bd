#pragma once
// Line plots rendered to PNG by gnuplot (Debian package gnuplot-nox, pngcairo terminal). The data
// and the script are kept beside the PNG (.dat, .gp), so a figure can be restyled and redrawn
// with `gnuplot FILE.gp` without rerunning anything.

#include <Eigen/Core>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace stocs::tools {

struct PlotSeries {
  std::string name;
  std::vector<Eigen::Vector2d> points;
};

struct LinePlot {
  std::string title;
  std::string x_label;
  std::string y_label;
  double x_min = std::numeric_limits<double>::quiet_NaN();  ///< NaN: automatic
  double x_max = std::numeric_limits<double>::quiet_NaN();
  double y_min = std::numeric_limits<double>::quiet_NaN();
  double y_max = std::numeric_limits<double>::quiet_NaN();
  bool log_x = false;
  bool markers = true;             ///< points marked on the lines
  std::vector<PlotSeries> series;  ///< series without points are left out
};

/// The gnuplot program, or an empty string when it is not installed.
std::string findGnuplot();

/// Writes `png` (and FILE.dat, FILE.gp beside it). Throws InputError with gnuplot's message when
/// it fails.
void renderPlot(const LinePlot& plot, const std::filesystem::path& png);

}  // namespace stocs::tools
