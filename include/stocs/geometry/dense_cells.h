#pragma once
// The cell layout shared by PointGrid and NeighbourhoodGrid: a uniform grid over a box, indexed
// densely (x fastest) rather than hashed, whose cells grow when the box would need too many, and
// the counting sort that fills its per-cell lists.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace stocs {

struct DenseCells {
  Eigen::Vector3f origin = Eigen::Vector3f::Zero();  // minimum corner of the box
  float size = 0, inv_size = 0;                      // cell side and its inverse
  size_t dims[3] = {0, 0, 0};                        // cells per axis

  /// Cells of at least `min_size` over the box [lo, lo + extent], far faces included, grown until
  /// there are at most `max_cells` (each step at least halves the count): a sparse set spread over
  /// a wide box must not allocate a huge index.
  static DenseCells cover(const Eigen::Vector3f& lo, const Eigen::Vector3f& extent, float min_size,
                          double max_cells) {
    auto cellsFor = [&](float size) {
      double cells = 1;
      for (int a = 0; a < 3; ++a) cells *= std::floor(extent[a] / size) + 1;
      return cells;
    };
    float size = min_size;
    while (cellsFor(size) > max_cells) {
      size *= std::max(1.26f, static_cast<float>(std::cbrt(cellsFor(size) / max_cells)));
    }
    DenseCells cells;
    cells.origin = lo;
    cells.size = size;
    cells.inv_size = 1.0f / size;
    for (int a = 0; a < 3; ++a) {
      cells.dims[a] = static_cast<size_t>(std::floor(extent[a] * cells.inv_size)) + 1;
    }
    return cells;
  }

  size_t count() const { return dims[0] * dims[1] * dims[2]; }
  size_t index(size_t x, size_t y, size_t z) const { return (z * dims[1] + y) * dims[0] + x; }
};

/// Counting sort of `items` items into `cells` cells: cellsOf(item, emit) calls emit(cell) for
/// every cell that lists the item. On return the items of cell c are list[start[c] .. start[c +
/// 1]), in item order. Both vectors are reused.
template <class CellsOf>
void sortIntoCells(size_t cells, uint32_t items, CellsOf&& cellsOf, std::vector<uint32_t>& start,
                   std::vector<uint32_t>& list) {
  // Counts go two cells up, so that after the prefix sum start[c + 1] is where cell c begins: the
  // fill advances it to where cell c ends, which is start[c + 1] of the result, with no pass to
  // shift the cursors back.
  start.assign(cells + 2, 0);
  for (uint32_t i = 0; i < items; ++i) cellsOf(i, [&](size_t c) { ++start[c + 2]; });
  for (size_t c = 2; c <= cells + 1; ++c) start[c] += start[c - 1];
  list.resize(start[cells + 1]);
  for (uint32_t i = 0; i < items; ++i) cellsOf(i, [&](size_t c) { list[start[c + 1]++] = i; });
  start.pop_back();
}

}  // namespace stocs
