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
//
// A focused draw (BaseWeighting::kFocused) takes every point in proportion to pi_k to the power
// BaseSamplerParams::focus_exponent instead of pi_k; StocsEstimator uses it for an object's first
// bases (StocsParams::focused_bases).

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

#include "stocs/estimation/stages/soft_segment.h"
#include "stocs/geometry/point_grid.h"
#include "stocs/model/ppf_hash_map.h"
#include "stocs/util/param_set.h"
#include "stocs/util/random.h"

namespace stocs {

struct BaseSamplerParams {
  float wide_angle_deg = 15.0f;  ///< epsilon_1: min angle at b1 between b1b2 and b1b3 (and to 180)
  float coplanarity = 0.005f;    ///< epsilon_2: max distance of b4 from plane(b1, b2, b3), metres
  int max_attempts = 20;         ///< fresh draws of b1 before a base counts as failed
  /// Power of pi_k in focused draws. A network's map is graded: the more confident its pixels, the
  /// more of them lie on the object. Drawn by pi_k^6, a base lies on the object far more often,
  /// while every point still counts in the objective with its pi_k.
  int focus_exponent = 6;
  static constexpr int kMaxFocusExponent = 16;

  /// Key, range, unit and meaning of every field (docs/parameters.md).
  static const ParamSet<BaseSamplerParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
};

/// Indices of the four base points in the segment.
using Base = std::array<int, 4>;

/// How a draw weighs the segment's points: by pi_k (the paper) or by pi_k^focus_exponent.
enum class BaseWeighting { kSegment, kFocused };

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
  /// The sampler keeps references: temporaries would dangle.
  BaseSampler(SoftSegment&&, const PpfHashMap&, const BaseSamplerParams&) = delete;
  BaseSampler(const SoftSegment&, PpfHashMap&&, const BaseSamplerParams&) = delete;

  /// A base, or nothing when `max_attempts` draws of b1 all led to a point with zero weight.
  std::optional<Base> sample(Rng& rng, BaseSamplingScratch& scratch,
                             BaseWeighting weighting = BaseWeighting::kSegment) const;

 private:
  /// The points' weights under one weighting, as prefix sums (zero on region boundaries).
  struct Weights {
    std::vector<double> cumulative;       // in the segment's order, for drawing b1
    std::vector<double> grid_cumulative;  // in the grid's sorted order, for b2, b3 and b4
    /// The weight of point i.
    double of(int i) const;
  };
  /// pi_k^exponent of every point.
  Weights weigh(int exponent) const;

  /// Finds the grid runs around b1 and their weights; false when they weigh nothing.
  bool gatherNeighbourhood(const Weights& w, int b1, BaseSamplingScratch& scratch) const;
  /// A point drawn by weight from the runs of gatherNeighbourhood.
  int drawNear(const Weights& w, Rng& rng, const BaseSamplingScratch& scratch) const;
  /// A point drawn by weight among the points of the runs that are both `geometric` (cheap tests)
  /// and `on_model` (PPF checks, the costly ones), or -1 when there is none.
  template <class Geometric, class OnModel>
  int drawConditional(const Weights& w, Rng& rng, Geometric&& geometric, OnModel&& on_model,
                      BaseSamplingScratch& scratch) const;
  bool tryComplete(const Weights& w, Rng& rng, Base& base, BaseSamplingScratch& scratch) const;

  const SoftSegment& segment_;
  const PpfHashMap& map_;
  BaseSamplerParams params_;
  PointGrid grid_;           // the segment in cells of the model's longest pair
  Weights segment_weights_;  // pi_k
  Weights focused_weights_;  // pi_k^focus_exponent
  float reach_;              // the model's longest pair, metres
  float cos_wide_;
};

}  // namespace stocs
