#include "stocs/neighbourhood_grid.h"

#include <numeric>
#include <stdexcept>

namespace stocs {

namespace {
std::vector<uint32_t> allIndices(size_t n) {
  std::vector<uint32_t> all(n);
  std::iota(all.begin(), all.end(), 0u);
  return all;
}
}  // namespace

NeighbourhoodGrid::NeighbourhoodGrid(const std::vector<Eigen::Vector3f>& points, float radius)
    : NeighbourhoodGrid(points, allIndices(points.size()), radius) {}

NeighbourhoodGrid::NeighbourhoodGrid(const std::vector<Eigen::Vector3f>& points,
                                     const std::vector<uint32_t>& subset, float radius)
    : radius_(radius), radius2_(radius * radius), inv_radius_(1.0f / radius) {
  if (!(radius > 0)) throw std::invalid_argument("NeighbourhoodGrid radius must be positive");
  auto forEachNeighbourCell = [&](const Eigen::Vector3f& p, auto&& f) {
    const Eigen::Vector3i c = voxelCell(p, inv_radius_);
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) f(packVoxelCell(c + Eigen::Vector3i(dx, dy, dz)));
      }
    }
  };
  // Counting sort into the cells around each point: count (in `end`), offsets, then fill.
  // A surface's cells and their neighbours number a few times its points, far below the 27 per
  // point of the worst case; the table grows if needed.
  table_.reserve(4 * subset.size());
  points_.reserve(subset.size());
  original_.reserve(subset.size());
  for (uint32_t i : subset) {
    points_.push_back(points[i]);
    original_.push_back(i);
    forEachNeighbourCell(points[i], [&](uint64_t key) { ++table_.findOrInsert(key).end; });
  }
  uint32_t total = 0;
  table_.forEachRange([&](CellTable::Range& r) {
    r.begin = total;
    total += r.end;
    r.end = r.begin;  // fill cursor
  });
  lists_.resize(total);
  for (uint32_t j = 0; j < points_.size(); ++j) {
    forEachNeighbourCell(points_[j],
                         [&](uint64_t key) { lists_[table_.findOrInsert(key).end++] = j; });
  }
}

}  // namespace stocs
