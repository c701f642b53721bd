#pragma once
// Stage 1 of StoCS: sampling a 4-point base on the soft segment (paper Algorithm 2).
//
// b1 is drawn from pi_k. Each next point is drawn from pi_k times the edge potential phi with every
// point already in the base (phi = the pair's PPF exists on the model), so all six base pairs are
// PPF-consistent. b3 must make a wide angle with b1b2 (epsilon_1) and b4 must lie near the plane of
// b1 b2 b3 (epsilon_2, metres). Algorithm 2 as printed zeroes the points that *satisfy* these
// tests; the text says the thresholds ensure "a wide interior angle" and coplanarity, which is what
// is implemented here.
//
// When the segment carries instance regions (labelRegions), b1 is never a boundary point and all
// four points come from b1's region, as in the authors' instance-aware sampling for packed bins.

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

#include "stocs/ppf_hash_map.h"
#include "stocs/random.h"
#include "stocs/soft_segment.h"

namespace stocs {

struct BaseSamplerParams {
  float wide_angle_deg = 15.0f;  ///< epsilon_1: min angle at b1 between b1b2 and b1b3 (and to 180)
  float coplanarity = 0.005f;    ///< epsilon_2: max distance of b4 from plane(b1, b2, b3), metres
  int max_attempts = 20;         ///< fresh draws of b1 before a base counts as failed

  /// Throws InputError naming the first value out of range.
  void validate() const;
};

/// Indices of the four base points in the segment.
using Base = std::array<int, 4>;

class BaseSampler {
 public:
  BaseSampler(const SoftSegment& segment, const PpfHashMap& map, const BaseSamplerParams& params);

  /// A base, or nothing when `max_attempts` draws of b1 all led to a point with zero weight.
  /// `scratch` is reused between calls to avoid allocation.
  std::optional<Base> sample(Rng& rng, std::vector<std::pair<int, float>>& scratch) const;

 private:
  /// A point drawn from pi_k (boundary points excluded when there are regions).
  int drawFirst(Rng& rng) const;
  /// A point drawn from pi_k restricted to `admissible` points, or -1 when there is none.
  template <class Admissible>
  int drawConditional(Rng& rng, Admissible&& admissible,
                      std::vector<std::pair<int, float>>& candidates) const;
  bool tryComplete(Rng& rng, Base& base, std::vector<std::pair<int, float>>& candidates) const;

  const SoftSegment& segment_;
  const PpfHashMap& map_;
  BaseSamplerParams params_;
  std::vector<double> cumulative_;  // prefix sums of pi_k for drawing b1
  float cos_wide_;
};

}  // namespace stocs
