#include "stocs/point_grid.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace stocs {

PointGrid::PointGrid(const std::vector<Eigen::Vector3f>& points, float cell_size)
    : cell_size_(cell_size), inv_cell_(1.0f / cell_size) {
  if (!(cell_size > 0)) throw std::invalid_argument("PointGrid cell size must be positive");
  std::vector<uint64_t> keys(points.size());
  for (size_t i = 0; i < points.size(); ++i) keys[i] = packVoxelCell(cellOf(points[i]));
  std::vector<uint32_t> order(points.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](uint32_t a, uint32_t b) { return keys[a] < keys[b]; });
  points_.resize(points.size());
  index_ = order;
  for (size_t k = 0; k < order.size(); ++k) points_[k] = points[order[k]];

  size_t cells = 0;
  for (size_t k = 0; k < order.size(); ++k)
    cells += (k == 0 || keys[order[k]] != keys[order[k - 1]]);
  table_.reserve(cells);
  for (size_t k = 0; k < order.size();) {
    size_t end = k;
    while (end < order.size() && keys[order[end]] == keys[order[k]]) ++end;
    table_.findOrInsert(keys[order[k]]) = {static_cast<uint32_t>(k), static_cast<uint32_t>(end)};
    k = end;
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
