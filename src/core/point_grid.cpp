#include "stocs/point_grid.h"

#include <stdexcept>

namespace stocs {
namespace {

/// Cells allowed per point before the cells grow (DenseCells::cover).
constexpr size_t kCellsPerPoint = 8;

}  // namespace

void PointGrid::assign(const std::vector<Eigen::Vector3f>& points, float cell_size) {
  if (!(cell_size > 0)) throw std::invalid_argument("PointGrid cell size must be positive");
  points_.clear();
  index_.clear();
  if (points.empty()) {
    cells_ = DenseCells{};
    cells_.size = cell_size;
    return;
  }
  Eigen::Vector3f lo = points.front(), hi = points.front();
  for (const Eigen::Vector3f& p : points) {
    // Per point: a NaN would slip through the bounding box (min and max ignore it) into a cell.
    if (!p.allFinite()) throw std::invalid_argument("PointGrid points must be finite");
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  cells_ =
      DenseCells::cover(lo, hi - lo, cell_size,
                        static_cast<double>(std::max<size_t>(64, kCellsPerPoint * points.size())));
  // Each point's cell once, for both passes of the sort (rebuilt per base: it is a hot path).
  cell_.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    size_t c[3];
    for (int a = 0; a < 3; ++a) {
      // The bounding box's far faces can round onto one cell past the last.
      // Through uint32_t: a float to size_t conversion costs a compare and a branch on x86-64.
      c[a] = std::min<size_t>(
          static_cast<uint32_t>((points[i][a] - cells_.origin[a]) * cells_.inv_size),
          cells_.dims[a] - 1);
    }
    cell_[i] = cells_.index(c[0], c[1], c[2]);
  }
  sortIntoCells(
      cells_.count(), static_cast<uint32_t>(points.size()),
      [&](uint32_t i, auto&& emit) { emit(cell_[i]); }, start_, index_);
  points_.resize(points.size());
  for (size_t k = 0; k < index_.size(); ++k) points_[k] = points[index_[k]];
}

int PointGrid::closestWithin(const Eigen::Vector3f& q, float radius, float* distance_sq) const {
  int best = -1;
  float best_d2 = radius * radius;
  forEachWithin(q, radius, [&](int index, float d2) {
    if (d2 < best_d2 || (d2 == best_d2 && best >= 0 && index < best)) {
      best = index;
      best_d2 = d2;
    }
  });
  if (distance_sq && best >= 0) *distance_sq = best_d2;
  return best;
}

}  // namespace stocs
