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

/// Cells allowed per point before the cells grow beyond half the radius (DenseCells::cover; larger
/// cells keep the lists exact, only longer).
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
  cells_ = DenseCells::cover(lo - Eigen::Vector3f::Constant(radius),
                             hi - lo + Eigen::Vector3f::Constant(2 * radius), radius / 2,
                             kCellsPerPoint * static_cast<double>(points_.size()));
  for (int a = 0; a < 3; ++a) dims_f_[a] = static_cast<float>(cells_.dims[a]);

  // Every cell whose box comes strictly within the radius of a point lists it; the reach is a hair
  // longer, so that rounding in the cell of a query can never leave out a point within the radius
  // (queries test the exact radius).
  const float reach = radius * (1 + 1e-4f);
  const float reach2 = reach * reach;
  const float cell = cells_.size;
  auto cellsNear = [&](uint32_t j, auto&& emit) {
    const Eigen::Vector3f& p = points_[j];
    size_t lo_cell[3], hi_cell[3];
    for (int a = 0; a < 3; ++a) {
      const float from = (p[a] - reach - cells_.origin[a]) * cells_.inv_size;
      const float to = (p[a] + reach - cells_.origin[a]) * cells_.inv_size;
      lo_cell[a] = static_cast<size_t>(std::max(0.0f, std::floor(from)));
      hi_cell[a] =
          std::min(cells_.dims[a] - 1, static_cast<size_t>(std::max(0.0f, std::floor(to))));
    }
    for (size_t z = lo_cell[2]; z <= hi_cell[2]; ++z) {
      const float box_z = cells_.origin.z() + static_cast<float>(z) * cell;
      const float dz = std::max({box_z - p.z(), p.z() - (box_z + cell), 0.0f});
      for (size_t y = lo_cell[1]; y <= hi_cell[1]; ++y) {
        const float box_y = cells_.origin.y() + static_cast<float>(y) * cell;
        const float dy = std::max({box_y - p.y(), p.y() - (box_y + cell), 0.0f});
        const float dzy2 = dz * dz + dy * dy;
        if (dzy2 >= reach2) continue;
        for (size_t x = lo_cell[0]; x <= hi_cell[0]; ++x) {
          const float box_x = cells_.origin.x() + static_cast<float>(x) * cell;
          const float dx = std::max({box_x - p.x(), p.x() - (box_x + cell), 0.0f});
          if (dzy2 + dx * dx < reach2) emit(cells_.index(x, y, z));
        }
      }
    }
  };
  sortIntoCells(cells_.count(), static_cast<uint32_t>(points_.size()), cellsNear, start_, lists_);
}

}  // namespace stocs
