#pragma once
// Nearest-point queries within a fixed radius, for the verification inner loop. Cells of the radius
// each list every point within the radius of any place in the cell, contiguously, so a query is one
// cell lookup and a scan of a short list (cells of the radius and their 27-cell neighbourhood would
// scan about as many points behind 27 lookups; cells of half the radius scan fewer but cost four
// times the entries and memory). Building costs about 21 entries per point (the cells within the
// radius of it on average), which pays off when, as in scoring, queries outnumber points by orders
// of magnitude. The lists hold 4-byte indices into one copy of the points.
//
// The cells come in blocks of 4 x 4 x 4, stored only where points are, found through a dense index
// of blocks over the points' bounding box grown by the radius. A segment's points lie on surfaces
// spread over a box up to a metre or more wide (background pixels above the probability
// threshold), where one dense index of cells would need millions of them; capping their number
// instead would grow the cells well beyond the radius on such segments, and the scans with them.
// The blocks cost one more load per query and no hashing.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "stocs/geometry/dense_cells.h"

namespace stocs {

class NeighbourhoodGrid {
 public:
  NeighbourhoodGrid() = default;
  NeighbourhoodGrid(const std::vector<Eigen::Vector3f>& points, float radius);
  /// Only the points whose indices are in `subset`; queries still report indices into `points`.
  NeighbourhoodGrid(const std::vector<Eigen::Vector3f>& points, const std::vector<uint32_t>& subset,
                    float radius);

  float radius() const { return radius_; }
  /// Side of the cells, metres: the radius, unless the points are so scattered that the cells
  /// grew (a memory bound; queries stay exact).
  float cellSize() const { return cell_size_; }

  /// Calls visit(index, distance_sq) for every point strictly within the radius of q.
  template <class Visit>
  void forEachWithin(const Eigen::Vector3f& q, Visit&& visit) const {
    const Eigen::Vector3f c = (q - blocks_.origin) * inv_cell_;
    // Negated comparisons also turn away NaN; the casts below are then within the grid.
    if (!(c.x() >= 0 && c.y() >= 0 && c.z() >= 0 && c.x() < dims_f_.x() && c.y() < dims_f_.y() &&
          c.z() < dims_f_.z())) {
      return;
    }
    // Through uint32_t: a float to size_t conversion costs a compare and a branch on x86-64.
    const size_t x = static_cast<uint32_t>(c.x()), y = static_cast<uint32_t>(c.y()),
                 z = static_cast<uint32_t>(c.z());
    const uint32_t block =
        block_of_[blocks_.index(x >> kBlockBits, y >> kBlockBits, z >> kBlockBits)];
    if (block == kNoBlock) return;
    const size_t cell = cellIndex(block, x, y, z);
    for (uint32_t k = start_[cell], end = start_[cell + 1]; k < end; ++k) {
      const uint32_t j = lists_[k];
      const float d2 = (points_[j] - q).squaredNorm();
      if (d2 < radius2_) visit(static_cast<int>(original_[j]), d2);
    }
  }

  /// Index of the closest point strictly within the radius of q among those `accept(index)` keeps,
  /// or -1; ties go to the lower index.
  template <class Accept>
  int closest(const Eigen::Vector3f& q, Accept&& accept) const {
    int best = -1;
    float best_d2 = radius2_;
    forEachWithin(q, [&](int index, float d2) {
      if (!accept(index)) return;
      if (d2 < best_d2 || (d2 == best_d2 && index < best)) {
        best = index;
        best_d2 = d2;
      }
    });
    return best;
  }
  int closest(const Eigen::Vector3f& q) const {
    return closest(q, [](int) { return true; });
  }

 private:
  static constexpr int kBlockBits = 2;  // blocks of 2^2 cells a side
  static constexpr size_t kBlockSide = size_t{1} << kBlockBits;
  static constexpr size_t kCellsPerBlock = kBlockSide * kBlockSide * kBlockSide;
  static constexpr uint32_t kNoBlock = UINT32_MAX;

  // The constructor's stages. `reach` is the radius and a hair: see the constructor.
  /// Copies the subset's points into points_ and original_ and gives their bounding box; throws
  /// std::invalid_argument for a point that is not finite.
  void copyPoints(const std::vector<Eigen::Vector3f>& points, const std::vector<uint32_t>& subset,
                  Eigen::Vector3f& lo, Eigen::Vector3f& hi);
  /// Sizes the cells (the radius, grown while the blocks in reach of the points would hold too
  /// many) and stores the blocks in reach; returns how many are stored.
  uint32_t layOutBlocks(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, float reach);
  /// Numbers the blocks within reach of some point in order of first use (block_of_); returns how
  /// many there are.
  uint32_t numberBlocks(float reach);
  /// The cells that may come within reach of point j: [lo_cell, hi_cell] per axis.
  void cellRange(uint32_t j, float reach, size_t (&lo_cell)[3], size_t (&hi_cell)[3]) const;
  /// Calls emit(cell index) for every stored cell within reach of point j; per row of cells (y,
  /// z) near the point, the cells of the row within reach form one run.
  template <class Emit>
  void forEachCellNear(uint32_t j, float reach, Emit&& emit) const;
  /// Lists every point in each stored cell within its reach (start_, lists_).
  void fillLists(uint32_t stored, float reach);

  /// Index of cell (x, y, z) (whole-grid cell coordinates) inside its stored block.
  static size_t cellIndex(uint32_t block, size_t x, size_t y, size_t z) {
    constexpr size_t m = kBlockSide - 1;
    return (static_cast<size_t>(block) << (3 * kBlockBits)) | ((z & m) << (2 * kBlockBits)) |
           ((y & m) << kBlockBits) | (x & m);
  }

  float radius_ = 0, radius2_ = 0;
  DenseCells blocks_;  // the block index, over the points' bounding box grown by the radius
  float cell_size_ = 0, inv_cell_ = 0;
  Eigen::Vector3f dims_f_ =
      Eigen::Vector3f::Zero();           // cells per axis as floats, for the bounds test
  std::vector<uint32_t> block_of_;       // per block of blocks_: its place among the stored blocks
  std::vector<Eigen::Vector3f> points_;  // the subset's points
  std::vector<uint32_t> original_;       // index of points_[j] in the constructor's vector
  std::vector<uint32_t> start_;  // list of stored cell c: lists_[start_[c] .. start_[c + 1])
  std::vector<uint32_t> lists_;  // indices into points_, concatenated
};

}  // namespace stocs
