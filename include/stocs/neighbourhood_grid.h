#pragma once
// Nearest-point queries within a fixed radius, for the verification inner loop. Each occupied cell
// (side = the radius) lists the points of its 27-neighbourhood contiguously, so a query is one hash
// lookup and one linear scan, with no pointer chasing. Building costs 27 entries per point, which
// pays off when, as in scoring, the queries outnumber the points by orders of magnitude. The lists
// hold 4-byte indices into one copy of the points rather than copies of the points and their
// indices, a quarter of the memory at the same query time.

#include <Eigen/Core>
#include <vector>

#include "stocs/cell_table.h"
#include "stocs/voxel_key.h"

namespace stocs {

class NeighbourhoodGrid {
 public:
  NeighbourhoodGrid() = default;
  NeighbourhoodGrid(const std::vector<Eigen::Vector3f>& points, float radius);
  /// Only the points whose indices are in `subset`; queries still report indices into `points`.
  NeighbourhoodGrid(const std::vector<Eigen::Vector3f>& points, const std::vector<uint32_t>& subset,
                    float radius);

  float radius() const { return radius_; }

  /// Calls visit(index, distance_sq) for every point strictly within the radius of q.
  template <class Visit>
  void forEachWithin(const Eigen::Vector3f& q, Visit&& visit) const {
    const CellTable::Range* r = table_.find(packVoxelCell(voxelCell(q, inv_radius_)));
    if (!r) return;
    for (uint32_t k = r->begin; k < r->end; ++k) {
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
  float radius_ = 0, radius2_ = 0, inv_radius_ = 0;
  std::vector<Eigen::Vector3f> points_;  // the subset's points
  std::vector<uint32_t> original_;       // index of points_[j] in the constructor's vector
  std::vector<uint32_t> lists_;  // neighbourhood lists of indices into points_, concatenated
  CellTable table_;              // cell -> its neighbourhood list
};

}  // namespace stocs
