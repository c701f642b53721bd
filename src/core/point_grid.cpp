#include "stocs/point_grid.h"

#include <cmath>
#include <stdexcept>

namespace stocs {

PointGrid::PointGrid(const std::vector<Eigen::Vector3f>& points, float cell_size)
    : cell_size_(cell_size), inv_cell_(1.0f / cell_size) {
  if (!(cell_size > 0)) throw std::invalid_argument("PointGrid cell size must be positive");
  // Counting sort by cell (count, offsets, fill): linear time, and each cell keeps its points in
  // index order.
  std::vector<uint64_t> keys(points.size());
  table_.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    keys[i] = packVoxelCell(cellOf(points[i]));
    ++table_.findOrInsert(keys[i]).end;
  }
  uint32_t total = 0;
  table_.forEachRange([&](CellTable::Range& r) {
    r.begin = total;
    total += r.end;
    r.end = r.begin;  // fill cursor
  });
  points_.resize(points.size());
  index_.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    CellTable::Range& r = table_.findOrInsert(keys[i]);
    points_[r.end] = points[i];
    index_[r.end++] = static_cast<uint32_t>(i);
  }
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
