#include "stocs/point_grid.h"

#include <stdexcept>

namespace stocs {
namespace {

/// Cells allowed per point before the cells grow: a sparse cloud spread over a wide box must not
/// allocate a huge index.
constexpr size_t kCellsPerPoint = 8;

}  // namespace

void PointGrid::assign(const std::vector<Eigen::Vector3f>& points, float cell_size) {
  if (!(cell_size > 0)) throw std::invalid_argument("PointGrid cell size must be positive");
  points_.clear();
  index_.clear();
  if (points.empty()) {
    cell_size_ = cell_size;
    inv_cell_ = 1.0f / cell_size;
    return;
  }
  Eigen::Vector3f lo = points.front(), hi = points.front();
  for (const Eigen::Vector3f& p : points) {
    // Per point: a NaN would slip through the bounding box (min and max ignore it) into a cell.
    if (!p.allFinite()) throw std::invalid_argument("PointGrid points must be finite");
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector3f extent = hi - lo;
  const double max_cells =
      static_cast<double>(std::max<size_t>(64, kCellsPerPoint * points.size()));
  auto cellsFor = [&](float size) {
    double cells = 1;
    for (int a = 0; a < 3; ++a) cells *= std::floor(extent[a] / size) + 1;
    return cells;
  };
  // Scale the cells up until the index is small enough (each step at least halves the count).
  while (cellsFor(cell_size) > max_cells) {
    cell_size *= std::max(1.26f, static_cast<float>(std::cbrt(cellsFor(cell_size) / max_cells)));
  }
  cell_size_ = cell_size;
  inv_cell_ = 1.0f / cell_size;
  origin_ = lo;
  for (int a = 0; a < 3; ++a) dims_[a] = static_cast<int>(std::floor(extent[a] * inv_cell_)) + 1;

  // Counting sort by cell: each cell keeps its points in index order.
  const size_t cells = static_cast<size_t>(dims_[0]) * dims_[1] * dims_[2];
  start_.assign(cells + 1, 0);
  cell_.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    size_t c = 0;
    for (int a = 2; a >= 0; --a) {
      // The bounding box's far faces can round onto one cell past the last.
      const int x =
          std::min(static_cast<int>((points[i][a] - origin_[a]) * inv_cell_), dims_[a] - 1);
      c = c * dims_[a] + static_cast<size_t>(x);
    }
    cell_[i] = static_cast<uint32_t>(c);
    ++start_[c + 1];
  }
  for (size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  points_.resize(points.size());
  index_.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const uint32_t k = start_[cell_[i]]++;  // start_[c] now runs as the fill cursor of cell c
    points_[k] = points[i];
    index_[k] = static_cast<uint32_t>(i);
  }
  // Each cursor ended at the next cell's start: shift back by one cell.
  for (size_t c = cells; c > 0; --c) start_[c] = start_[c - 1];
  start_[0] = 0;
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
