#include "stocs/neighbourhood_grid.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace stocs {

namespace {
std::vector<uint32_t> allIndices(size_t n) {
  std::vector<uint32_t> all(n);
  std::iota(all.begin(), all.end(), 0u);
  return all;
}

/// Cells allowed per point before the cells grow beyond half the radius: a sparse set spread over
/// a wide box must not allocate a huge index (larger cells keep the lists exact, only longer).
constexpr double kCellsPerPoint = 64;
}  // namespace

NeighbourhoodGrid::NeighbourhoodGrid(const std::vector<Eigen::Vector3f>& points, float radius)
    : NeighbourhoodGrid(points, allIndices(points.size()), radius) {}

NeighbourhoodGrid::NeighbourhoodGrid(const std::vector<Eigen::Vector3f>& points,
                                     const std::vector<uint32_t>& subset, float radius)
    : radius_(radius), radius2_(radius * radius) {
  if (!(radius > 0)) throw std::invalid_argument("NeighbourhoodGrid radius must be positive");
  start_.assign(1, 0);
  if (subset.empty()) return;  // every query falls outside the empty grid
  points_.reserve(subset.size());
  original_.reserve(subset.size());
  Eigen::Vector3f lo = points[subset.front()], hi = lo;
  for (uint32_t i : subset) {
    // Per point: a NaN would slip through the bounding box (min and max ignore it).
    if (!points[i].allFinite()) {
      throw std::invalid_argument("NeighbourhoodGrid points must be finite");
    }
    points_.push_back(points[i]);
    original_.push_back(i);
    lo = lo.cwiseMin(points[i]);
    hi = hi.cwiseMax(points[i]);
  }
  origin_ = lo - Eigen::Vector3f::Constant(radius);
  const Eigen::Vector3f extent = hi - lo + Eigen::Vector3f::Constant(2 * radius);
  float cell = radius / 2;
  auto cellsFor = [&](float size) {
    double cells = 1;
    for (int a = 0; a < 3; ++a) cells *= std::ceil(extent[a] / size);
    return cells;
  };
  const double max_cells = kCellsPerPoint * static_cast<double>(points_.size());
  while (cellsFor(cell) > max_cells) cell *= 1.26f;  // about halves the count per step
  inv_cell_ = 1.0f / cell;
  for (int a = 0; a < 3; ++a) {
    dims_[a] = static_cast<size_t>(std::ceil(extent[a] * inv_cell_));
    dims_f_[a] = static_cast<float>(dims_[a]);
  }

  // Every cell whose box comes strictly within the radius of a point lists it; the reach is a hair
  // longer, so that rounding in the cell of a query can never leave out a point within the radius
  // (queries test the exact radius). Counting sort: count, offsets, fill.
  const float reach = radius * (1 + 1e-4f);
  const float reach2 = reach * reach;
  auto forEachCellNear = [&](const Eigen::Vector3f& p, auto&& f) {
    size_t lo_cell[3], hi_cell[3];
    for (int a = 0; a < 3; ++a) {
      const float from = (p[a] - reach - origin_[a]) * inv_cell_;
      const float to = (p[a] + reach - origin_[a]) * inv_cell_;
      lo_cell[a] = static_cast<size_t>(std::max(0.0f, std::floor(from)));
      hi_cell[a] = std::min(dims_[a] - 1, static_cast<size_t>(std::max(0.0f, std::floor(to))));
    }
    for (size_t z = lo_cell[2]; z <= hi_cell[2]; ++z) {
      const float box_z = origin_.z() + static_cast<float>(z) * cell;
      const float dz = std::max({box_z - p.z(), p.z() - (box_z + cell), 0.0f});
      for (size_t y = lo_cell[1]; y <= hi_cell[1]; ++y) {
        const float box_y = origin_.y() + static_cast<float>(y) * cell;
        const float dy = std::max({box_y - p.y(), p.y() - (box_y + cell), 0.0f});
        const float dzy2 = dz * dz + dy * dy;
        if (dzy2 >= reach2) continue;
        for (size_t x = lo_cell[0]; x <= hi_cell[0]; ++x) {
          const float box_x = origin_.x() + static_cast<float>(x) * cell;
          const float dx = std::max({box_x - p.x(), p.x() - (box_x + cell), 0.0f});
          if (dzy2 + dx * dx < reach2) f((z * dims_[1] + y) * dims_[0] + x);
        }
      }
    }
  };
  const size_t cells = dims_[0] * dims_[1] * dims_[2];
  start_.assign(cells + 1, 0);
  for (const Eigen::Vector3f& p : points_) forEachCellNear(p, [&](size_t c) { ++start_[c + 1]; });
  for (size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  lists_.resize(start_[cells]);
  for (uint32_t j = 0; j < points_.size(); ++j) {
    forEachCellNear(points_[j], [&](size_t c) { lists_[start_[c]++] = j; });
  }
  // Each fill cursor ended at the next cell's start: shift back by one cell.
  for (size_t c = cells; c > 0; --c) start_[c] = start_[c - 1];
  start_[0] = 0;
}

}  // namespace stocs
