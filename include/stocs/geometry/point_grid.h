#pragma once
// Fixed-radius neighbour queries on a static point set through a uniform grid over the points'
// bounding box. Cells are indexed densely (x fastest) and the points sorted by cell, so the cells
// of one x-row of a query's neighbourhood hold one contiguous run of points: a query with a radius
// up to the cell size scans 9 runs, with no hashing and no allocation. Building is a counting sort
// (two passes, no hashing), cheap enough to rebuild for every base of the congruent-set search;
// `assign` reuses the buffers. A kd-tree would pay a log factor and pointer chasing instead.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "stocs/geometry/dense_cells.h"
#include "stocs/util/fast_floor.h"

namespace stocs {

class PointGrid {
 public:
  PointGrid() = default;
  /// Throws std::invalid_argument when cell_size is not positive or a point is not finite.
  PointGrid(const std::vector<Eigen::Vector3f>& points, float cell_size) {
    assign(points, cell_size);
  }

  /// Rebuilds the grid over `points` with cells of at least `cell_size` (larger when the bounding
  /// box would need more than a few cells per point), keeping the allocated buffers.
  void assign(const std::vector<Eigen::Vector3f>& points, float cell_size);

  bool empty() const { return points_.empty(); }
  float cellSize() const { return cells_.size; }

  /// Index (into the constructor's vector) of the point closest to q among those strictly within
  /// `radius`, or -1. Ties go to the lower index, so results never depend on the cell layout.
  int closestWithin(const Eigen::Vector3f& q, float radius, float* distance_sq = nullptr) const;

  /// Calls visit(index, distance_sq) for every point strictly within `radius` of q (q may lie
  /// anywhere, also outside the points' bounding box).
  template <class Visit>
  void forEachWithin(const Eigen::Vector3f& q, float radius, Visit&& visit) const {
    const float r2 = radius * radius;
    forEachRun(q, radius, [&](uint32_t begin, uint32_t end) {
      for (uint32_t k = begin; k < end; ++k) {
        const float d2 = (points_[k] - q).squaredNorm();
        if (d2 < r2) visit(static_cast<int>(index_[k]), d2);
      }
    });
  }

  /// Calls visit(begin, end) for runs of sorted positions [begin, end) that together hold every
  /// point within `radius` of q, among others of the same cells; originalIndex maps a position to
  /// the constructor's index. Positions follow the cells, so they cover each run contiguously.
  template <class Visit>
  void forEachRun(const Eigen::Vector3f& q, float radius, Visit&& visit) const {
    if (points_.empty()) return;
    const float reach = ceilFast(radius * cells_.inv_size);
    size_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      // In floats first: a query far outside the box must not overflow an integer.
      const float c = floorFast((q[a] - cells_.origin[a]) * cells_.inv_size);
      const float first = std::max(c - reach, 0.0f);
      const float last = std::min(c + reach, static_cast<float>(cells_.dims[a]) - 1.0f);
      if (!(first <= last)) return;
      lo[a] = static_cast<size_t>(first);
      hi[a] = static_cast<size_t>(last);
    }
    for (size_t z = lo[2]; z <= hi[2]; ++z) {
      for (size_t y = lo[1]; y <= hi[1]; ++y) {
        const uint32_t begin = start_[cells_.index(lo[0], y, z)],
                       end = start_[cells_.index(hi[0], y, z) + 1];
        if (begin < end) visit(begin, end);
      }
    }
  }

  size_t size() const { return points_.size(); }
  /// The constructor's index of the point at sorted position k.
  uint32_t originalIndex(uint32_t k) const { return index_[k]; }

 private:
  DenseCells cells_;                     // over the points' bounding box
  std::vector<Eigen::Vector3f> points_;  // sorted by cell
  std::vector<uint32_t> index_;          // original index of points_[k]
  std::vector<uint32_t> start_;          // points of cell c: points_[start_[c] .. start_[c + 1])
  std::vector<size_t> cell_;             // cell of each input point while building
};

}  // namespace stocs
