#pragma once
// Integer cells of a uniform 3D grid packed into one 64-bit key (21 bits per axis, about +-1e6
// cells: +-5 km at 5 mm cells).

#include <Eigen/Core>
#include <cstdint>

#include "stocs/util/fast_floor.h"

namespace stocs {

/// floorFast, not std::floor: the soft segment calls this for every pixel of the segment.
inline Eigen::Vector3i voxelCell(const Eigen::Vector3f& p, float inverse_cell_size) {
  return {static_cast<int>(floorFast(p.x() * inverse_cell_size)),
          static_cast<int>(floorFast(p.y() * inverse_cell_size)),
          static_cast<int>(floorFast(p.z() * inverse_cell_size))};
}

inline uint64_t packVoxelCell(const Eigen::Vector3i& c) {
  constexpr int64_t kBias = 1 << 20;
  constexpr uint64_t kMask = (1ull << 21) - 1;
  return ((static_cast<uint64_t>(c.x() + kBias) & kMask) << 42) |
         ((static_cast<uint64_t>(c.y() + kBias) & kMask) << 21) |
         (static_cast<uint64_t>(c.z() + kBias) & kMask);
}

}  // namespace stocs
