#pragma once
// Integer cells of a uniform 3D grid packed into one 64-bit key (21 bits per axis, about +-1e6
// cells: +-5 km at 5 mm cells).

#include <Eigen/Core>
#include <cmath>
#include <cstdint>

namespace stocs {

inline Eigen::Vector3i voxelCell(const Eigen::Vector3f& p, float inverse_cell_size) {
  return {static_cast<int>(std::floor(p.x() * inverse_cell_size)),
          static_cast<int>(std::floor(p.y() * inverse_cell_size)),
          static_cast<int>(std::floor(p.z() * inverse_cell_size))};
}

inline uint64_t packVoxelCell(const Eigen::Vector3i& c) {
  constexpr int64_t kBias = 1 << 20;
  constexpr uint64_t kMask = (1ull << 21) - 1;
  return ((static_cast<uint64_t>(c.x() + kBias) & kMask) << 42) |
         ((static_cast<uint64_t>(c.y() + kBias) & kMask) << 21) |
         (static_cast<uint64_t>(c.z() + kBias) & kMask);
}

}  // namespace stocs
