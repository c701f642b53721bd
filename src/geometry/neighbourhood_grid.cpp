#include "stocs/geometry/neighbourhood_grid.h"

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

/// Memory bounds, after which the cells grow beyond the radius (queries stay exact, the lists get
/// longer): entries of the block index per point, and stored cells per point. Points on surfaces
/// share blocks and stay well below them; a scattered point stores up to 8 blocks of 64.
constexpr double kBlocksPerPoint = 64;
constexpr double kCellsPerPoint = 256;
constexpr double kMinCells = 8 * 64;  // 8 blocks: a few points need not share one huge cell

/// Cell coordinate of a grid coordinate, 0 below the grid: truncation is the floor there, and not
/// a libm call (see fast_floor.h; this runs for every row of cells near every point). Through
/// uint32_t: float to and from 64-bit unsigned integers costs a compare and a branch on x86-64,
/// and cell coordinates stay far below 2^32 (at most kCellsPerPoint cells per point).
inline size_t cellOf(float c) {
  return c > 0 ? size_t{static_cast<uint32_t>(c)} : size_t{0};
}
/// Grid coordinate of the low corner of cell `c` (through uint32_t, as cellOf).
inline float coordinate(size_t c) {
  return static_cast<float>(static_cast<uint32_t>(c));
}
}  // namespace

NeighbourhoodGrid::NeighbourhoodGrid(const std::vector<Eigen::Vector3f>& points, float radius)
    : NeighbourhoodGrid(points, allIndices(points.size()), radius) {}

NeighbourhoodGrid::NeighbourhoodGrid(const std::vector<Eigen::Vector3f>& points,
                                     const std::vector<uint32_t>& subset, float radius)
    : radius_(radius), radius2_(radius * radius) {
  if (!(radius > 0)) throw std::invalid_argument("NeighbourhoodGrid radius must be positive");
  start_.assign(1, 0);
  if (subset.empty()) return;  // every query falls outside the empty grid
  Eigen::Vector3f lo, hi;
  copyPoints(points, subset, lo, hi);
  // Every cell whose box comes strictly within the radius of a point lists it; the reach is a hair
  // longer, so that rounding in the cell of a query can never leave out a point within the radius
  // (queries test the exact radius).
  const float reach = radius * (1 + 1e-4f);
  const uint32_t stored = layOutBlocks(lo, hi, reach);
  fillLists(stored, reach);
}

void NeighbourhoodGrid::copyPoints(const std::vector<Eigen::Vector3f>& points,
                                   const std::vector<uint32_t>& subset, Eigen::Vector3f& lo,
                                   Eigen::Vector3f& hi) {
  points_.reserve(subset.size());
  original_.reserve(subset.size());
  lo = points[subset.front()];
  hi = lo;
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
}

void NeighbourhoodGrid::cellRange(uint32_t j, float reach, size_t (&lo_cell)[3],
                                  size_t (&hi_cell)[3]) const {
  const Eigen::Vector3f& p = points_[j];
  for (int a = 0; a < 3; ++a) {
    const float from = (p[a] - reach - blocks_.origin[a]) * inv_cell_;
    const float to = (p[a] + reach - blocks_.origin[a]) * inv_cell_;
    lo_cell[a] = cellOf(from);
    hi_cell[a] = std::min(blocks_.dims[a] * kBlockSide - 1, cellOf(to));
  }
}

uint32_t NeighbourhoodGrid::layOutBlocks(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi,
                                         float reach) {
  const auto n = static_cast<uint32_t>(points_.size());
  float cell = radius_;
  uint32_t stored = 0;
  for (;;) {
    blocks_ = DenseCells::cover(
        lo - Eigen::Vector3f::Constant(radius_), hi - lo + Eigen::Vector3f::Constant(2 * radius_),
        static_cast<float>(kBlockSide) * cell, std::max(kMinCells, kBlocksPerPoint * n));
    cell_size_ = blocks_.size / static_cast<float>(kBlockSide);
    inv_cell_ = 1.0f / cell_size_;
    stored = numberBlocks(reach);
    const double cells = static_cast<double>(stored) * static_cast<double>(kCellsPerBlock);
    if (cells <= std::max(kMinCells, kCellsPerPoint * n)) break;
    cell = cell_size_ * 1.26f;
  }
  for (int a = 0; a < 3; ++a) dims_f_[a] = static_cast<float>(blocks_.dims[a] * kBlockSide);
  return stored;
}

uint32_t NeighbourhoodGrid::numberBlocks(float reach) {
  block_of_.assign(blocks_.count(), kNoBlock);
  uint32_t stored = 0;
  const auto n = static_cast<uint32_t>(points_.size());
  for (uint32_t j = 0; j < n; ++j) {
    size_t lo_cell[3], hi_cell[3];
    cellRange(j, reach, lo_cell, hi_cell);
    for (size_t z = lo_cell[2] >> kBlockBits; z <= hi_cell[2] >> kBlockBits; ++z) {
      for (size_t y = lo_cell[1] >> kBlockBits; y <= hi_cell[1] >> kBlockBits; ++y) {
        for (size_t x = lo_cell[0] >> kBlockBits; x <= hi_cell[0] >> kBlockBits; ++x) {
          uint32_t& block = block_of_[blocks_.index(x, y, z)];
          if (block == kNoBlock) block = stored++;
        }
      }
    }
  }
  return stored;
}

template <class Emit>
void NeighbourhoodGrid::forEachCellNear(uint32_t j, float reach, Emit&& emit) const {
  const float reach2 = reach * reach;
  const Eigen::Vector3f& p = points_[j];
  size_t lo_cell[3], hi_cell[3];
  cellRange(j, reach, lo_cell, hi_cell);
  for (size_t z = lo_cell[2]; z <= hi_cell[2]; ++z) {
    const float box_z = blocks_.origin.z() + coordinate(z) * cell_size_;
    const float dz = std::max({box_z - p.z(), p.z() - (box_z + cell_size_), 0.0f});
    for (size_t y = lo_cell[1]; y <= hi_cell[1]; ++y) {
      const float box_y = blocks_.origin.y() + coordinate(y) * cell_size_;
      const float dy = std::max({box_y - p.y(), p.y() - (box_y + cell_size_), 0.0f});
      const float dzy2 = dz * dz + dy * dy;
      if (dzy2 >= reach2) continue;
      // The cells overlapping [p.x - w, p.x + w]: a superset of those strictly within reach at
      // the run's ends, which only lengthens two lists by rounding.
      const float w = std::sqrt(reach2 - dzy2);
      const size_t from =
          std::max(lo_cell[0], cellOf((p.x() - w - blocks_.origin.x()) * inv_cell_));
      const size_t to = std::min(hi_cell[0], cellOf((p.x() + w - blocks_.origin.x()) * inv_cell_));
      for (size_t x = from; x <= to; ++x) {
        const uint32_t block =
            block_of_[blocks_.index(x >> kBlockBits, y >> kBlockBits, z >> kBlockBits)];
        emit(cellIndex(block, x, y, z));
      }
    }
  }
}

void NeighbourhoodGrid::fillLists(uint32_t stored, float reach) {
  // Each point's cells once, for both passes of the sort: the geometry above costs more than
  // reading them back. Fewer than 2^32 cells: at most kCellsPerPoint per point. On average about
  // 21 cells of the radius lie within the radius of a point (Steiner's formula for a cube and a
  // ball: 1 + 6 + 3 pi + 4 pi / 3), hence the reserve.
  const auto n = static_cast<uint32_t>(points_.size());
  std::vector<uint32_t> near_cells, first_near(n + 1, 0);
  near_cells.reserve(static_cast<size_t>(n) * 32);
  for (uint32_t j = 0; j < n; ++j) {
    forEachCellNear(j, reach, [&](size_t c) { near_cells.push_back(static_cast<uint32_t>(c)); });
    first_near[j + 1] = static_cast<uint32_t>(near_cells.size());
  }
  sortIntoCells(
      stored * kCellsPerBlock, n,
      [&](uint32_t j, auto&& emit) {
        for (uint32_t k = first_near[j]; k < first_near[j + 1]; ++k) emit(near_cells[k]);
      },
      start_, lists_);
}

}  // namespace stocs
