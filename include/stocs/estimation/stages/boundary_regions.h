#pragma once
// The instance regions of a boundary map (CV_8UC1; values >= 128 are object interior, lower values
// are boundaries, as in the StoCS `edge.png` and the BOP `edge/` extension): the 4-connected
// components of interior pixels, numbered from 1 in raster order of their first pixel, as
// cv::connectedComponents numbers them; boundary pixels have region 0.
//
// Labelled by runs of interior pixels rather than with cv::connectedComponents: a segment needs the
// region of a few thousand pixels, not a 640x480 label image, and OpenCV's labelling runs on its
// own thread pool, which competes with the estimator's OpenMP threads for the cores. A boundary
// map is mostly long runs, so the scan steps 8 pixels at a time where nothing changes, and the
// union-find joins runs, not pixels.

#include <vector>

namespace cv {
class Mat;
}

namespace stocs {

class BoundaryRegions {
 public:
  /// Throws InputError unless `boundary_map` is a non-empty CV_8UC1 image.
  explicit BoundaryRegions(const cv::Mat& boundary_map);

  /// Number of regions (the largest region number).
  int count() const { return count_; }
  /// Region of pixel (u, v), 0 on a boundary. Expects (u, v) inside the map.
  int at(int u, int v) const;

 private:
  struct Run {
    int begin, end;  // columns [begin, end)
    int region;
  };
  int width_ = 0, height_ = 0, count_ = 0;
  std::vector<Run> runs_;        // in raster order
  std::vector<int> row_starts_;  // runs of row v: runs_[row_starts_[v] .. row_starts_[v + 1])
};

}  // namespace stocs
