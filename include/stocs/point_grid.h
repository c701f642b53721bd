#pragma once
// Fixed-radius neighbour queries on a static point set through a hashed uniform grid. Queries with
// a radius up to the cell size touch 27 cells, cost O(1) per query and allocate nothing, which is
// what the verification inner loop needs; a kd-tree would pay a log factor and pointer chasing
// instead.

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <vector>

#include "stocs/cell_table.h"
#include "stocs/voxel_key.h"

namespace stocs {

class PointGrid {
 public:
  PointGrid() = default;
  PointGrid(const std::vector<Eigen::Vector3f>& points, float cell_size);

  bool empty() const { return points_.empty(); }
  float cellSize() const { return cell_size_; }

  /// Index (into the constructor's vector) of the point closest to q among those strictly within
  /// `radius`, or -1. Ties go to the lower index, so results never depend on the table layout.
  int closestWithin(const Eigen::Vector3f& q, float radius, float* distance_sq = nullptr) const;

  /// Calls visit(index, distance_sq) for every point strictly within `radius` of q.
  template <class Visit>
  void forEachWithin(const Eigen::Vector3f& q, float radius, Visit&& visit) const {
    const float r2 = radius * radius;
    const int reach = static_cast<int>(std::ceil(radius * inv_cell_));
    const Eigen::Vector3i c = cellOf(q);
    for (int dx = -reach; dx <= reach; ++dx) {
      for (int dy = -reach; dy <= reach; ++dy) {
        for (int dz = -reach; dz <= reach; ++dz) {
          const CellTable::Range* s = table_.find(packVoxelCell(c + Eigen::Vector3i(dx, dy, dz)));
          if (!s) continue;
          for (uint32_t k = s->begin; k < s->end; ++k) {
            const float d2 = (points_[k] - q).squaredNorm();
            if (d2 < r2) visit(static_cast<int>(index_[k]), d2);
          }
        }
      }
    }
  }

 private:
  Eigen::Vector3i cellOf(const Eigen::Vector3f& p) const { return voxelCell(p, inv_cell_); }

  float cell_size_ = 0, inv_cell_ = 0;
  std::vector<Eigen::Vector3f> points_;  // grouped by cell for locality
  std::vector<uint32_t> index_;          // original index of points_[k]
  CellTable table_;                      // cell -> range of points_
};

}  // namespace stocs
