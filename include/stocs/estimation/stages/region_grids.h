#pragma once
// The neighbourhood grids of a segment at one radius: one over all its points and one per instance
// region. Without regions the grid of all points is built at once; with regions every base, and so
// every hypothesis and refinement, stays inside one region, and a frame's bases touch few of the
// regions: each grid is built on its first query rather than every one up front.

#include <Eigen/Core>
#include <cstdint>
#include <mutex>
#include <unordered_map>
#include <vector>

#include "stocs/geometry/neighbourhood_grid.h"

namespace stocs {

class RegionGrids {
 public:
  /// `region` holds a region per point (negative: on a boundary, in no region) or is empty. Both
  /// vectors must outlive this object.
  RegionGrids(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& region,
              float radius);
  RegionGrids(const RegionGrids&) = delete;
  RegionGrids& operator=(const RegionGrids&) = delete;

  /// The grid of the points of `region`, or of all points for a negative region or when there are
  /// no regions; a region without points has an empty grid. Safe to call from several threads.
  const NeighbourhoodGrid& of(int region) const;

 private:
  struct Lazy {
    std::vector<uint32_t> members;  // point indices; unused by the grid of all points
    mutable std::once_flag once;
    mutable NeighbourhoodGrid grid;
  };

  const std::vector<Eigen::Vector3f>& points_;
  float radius_;
  bool has_regions_;
  Lazy all_;
  std::unordered_map<int, Lazy> regions_;
  NeighbourhoodGrid empty_;
};

}  // namespace stocs
