#pragma once
// Point pair features (Drost et al. 2010) and their discretisation into integer keys.
// PPF(m1, m2) = (|d|, angle(n1, d), angle(n2, d), angle(n1, n2)) with d = m2 - m1.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace stocs {

struct PpfFeature {
  float distance = 0;
  float angle_n1_d = 0;
  float angle_n2_d = 0;
  float angle_n1_n2 = 0;
};

inline float clampedAcos(float c) {
  return std::acos(std::clamp(c, -1.0f, 1.0f));
}

/// Feature of the ordered pair (p1, p2) with unit normals n1, n2. Coincident points give distance 0
/// and zero angles.
inline PpfFeature computePpf(const Eigen::Vector3f& p1, const Eigen::Vector3f& n1,
                             const Eigen::Vector3f& p2, const Eigen::Vector3f& n2) {
  const Eigen::Vector3f d = p2 - p1;
  const float len = d.norm();
  if (!(len > 0)) return {};
  const Eigen::Vector3f u = d / len;
  return {len, clampedAcos(n1.dot(u)), clampedAcos(n2.dot(u)), clampedAcos(n1.dot(n2))};
}

/// Maps features to bins of `distance_step` metres and `angle_step` radians, and bins to dense
/// integer keys. A feature's "nearest bins" are, in each of the 4 dimensions, its own bin and the
/// neighbour on the side of the nearer bin edge: 2^4 bins, so values within half a bin of each
/// other always share a bin (the paper's voting into 2^4 neighbouring bins, done at query time).
class PpfQuantizer {
 public:
  static constexpr int kNearest = 16;
  using Keys = std::array<uint32_t, kNearest>;

  PpfQuantizer() = default;
  PpfQuantizer(float distance_step, float angle_step, float max_distance);

  float distanceStep() const { return distance_step_; }
  float angleStep() const { return angle_step_; }
  int distanceBins() const { return distance_bins_; }
  int angleBins() const { return angle_bins_; }
  uint32_t keyCount() const {
    return static_cast<uint32_t>(distance_bins_) * angle_bins_ * angle_bins_ * angle_bins_;
  }
  /// False when the bins are too many for 32-bit keys (keyCount and keys would wrap).
  bool keysFit() const {
    return uint64_t(distance_bins_) * angle_bins_ * angle_bins_ * angle_bins_ <= UINT32_MAX;
  }

  /// Key of the feature's own bin; false when the distance is beyond the range.
  bool key(const PpfFeature& f, uint32_t& out) const;

  /// Keys of the feature's nearest bins that lie in range, distinct; returns how many.
  int nearestKeys(const PpfFeature& f, Keys& out) const;

 private:
  uint32_t pack(int d, int a1, int a2, int a3) const {
    return ((static_cast<uint32_t>(d) * angle_bins_ + a1) * angle_bins_ + a2) * angle_bins_ + a3;
  }

  float distance_step_ = 0, angle_step_ = 0;
  int distance_bins_ = 0, angle_bins_ = 0;
};

}  // namespace stocs
