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
// b2, b3 and b4 must be PPF-consistent with b1, so they lie within the model's longest pair of b1:
// each is drawn among the points of the grid cells around b1 (cells of that length), never from a
// scan of the whole segment, which spreads over the background and other objects.
//
// When the segment carries instance regions (labelRegions), b1 is never a boundary point and all
// four points come from b1's region, as in the authors' instance-aware sampling for packed bins.

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

#include "stocs/point_grid.h"
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

/// Working memory of BaseSampler::sample, reused between calls to avoid allocation.
struct BaseSamplingScratch {
  std::vector<std::array<uint32_t, 2>> runs;  ///< grid positions [begin, end) around b1
  std::vector<double> run_cumulative;         ///< prefix sums of the runs' pi_k
  std::vector<int> points;                    ///< candidates of the later rounds of a draw
  std::vector<double> cumulative;             ///< prefix sums of their pi_k
};

class BaseSampler {
 public:
  BaseSampler(const SoftSegment& segment, const PpfHashMap& map, const BaseSamplerParams& params);

  /// A base, or nothing when `max_attempts` draws of b1 all led to a point with zero weight.
  std::optional<Base> sample(Rng& rng, BaseSamplingScratch& scratch) const;

 private:
  /// pi_k of point i (zero on region boundaries).
  double weight(int i) const;
  /// A point drawn from pi_k (boundary points excluded when there are regions).
  int drawFirst(Rng& rng) const;
  /// Finds the grid runs around b1 and their weights; false when they weigh nothing.
  bool gatherNeighbourhood(int b1, BaseSamplingScratch& scratch) const;
  /// A point drawn from pi_k restricted to the runs of gatherNeighbourhood.
  int drawNear(Rng& rng, const BaseSamplingScratch& scratch) const;
  /// A point drawn from pi_k restricted to the points of the runs that are both `geometric` (cheap
  /// tests) and `on_model` (PPF checks, the costly ones), or -1 when there is none.
  template <class Geometric, class OnModel>
  int drawConditional(Rng& rng, Geometric&& geometric, OnModel&& on_model,
                      BaseSamplingScratch& scratch) const;
  bool tryComplete(Rng& rng, Base& base, BaseSamplingScratch& scratch) const;

  const SoftSegment& segment_;
  const PpfHashMap& map_;
  BaseSamplerParams params_;
  std::vector<double> cumulative_;       // prefix sums of pi_k for drawing b1
  PointGrid grid_;                       // the segment in cells of the model's longest pair
  std::vector<double> grid_cumulative_;  // prefix sums of pi_k in the grid's sorted order
  float reach_;                          // the model's longest pair, metres
  float cos_wide_;
};

}  // namespace stocs
