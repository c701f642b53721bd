#pragma once
// The StoCS search (paper Algorithm 1) and its parameters. StocsEstimator::search is the driver:
// it runs the paper's stages (stages/: BaseSampler -> CongruentSetMatcher -> fitRigid ->
// LcpScorer per base, then point-to-plane refinement of the best bases) under the scheduling added
// around them (scheduling/: the bases shared out among threads, the consensus stop, early
// refinements, the time budget).
//
// Determinism: base b draws from its own random stream streamSeed(seed, b), and ties between equal
// scores go to the lower (base, set) index, so with a base limit and no time budget the result is
// the same for every thread count. A time budget makes the number of bases depend on the machine;
// the consensus stop does not (it is decided between whole blocks of bases, on exact scores).

#include <Eigen/Geometry>
#include <chrono>
#include <vector>

#include "stocs/estimation/pose_estimate.h"
#include "stocs/estimation/pose_proximity.h"
#include "stocs/estimation/stages/base_sampler.h"
#include "stocs/estimation/stages/congruent_set_matcher.h"
#include "stocs/estimation/stages/frame_evidence.h"
#include "stocs/estimation/stages/free_space_check.h"
#include "stocs/estimation/stages/icp_refiner.h"
#include "stocs/estimation/stages/lcp_scorer.h"
#include "stocs/estimation/stages/soft_segment.h"
#include "stocs/model/model_cache.h"
#include "stocs/util/param_set.h"

namespace stocs {

class EarlyRefinements;
struct BaseOutcome;
struct RefinementContext;

struct StocsParams {
  BaseSamplerParams base;
  CongruentSetParams congruent;
  float max_fit_rms = 0.008f;  ///< metres: congruent sets whose rigid fit is worse are dropped
  /// Metres: a hypothesis that moves no model point farther than this from a hypothesis already
  /// scored for the same base is a near-duplicate and is not scored (0 scores every one).
  float duplicate_distance = 0.0025f;
  /// A hypothesis is scored only when at least this many of the base's four points have the
  /// normal of their model point within delta_n under it (0 scores every one). Flat and
  /// symmetric faces give many fits that turn the model inside out (every normal reversed); they
  /// cannot score, so scoring them is wasted. One agreeing point suffices to keep every fit that
  /// is not turned over.
  int min_normal_agreement = 1;
  /// Of a base's hypotheses, only this many, those with the best objective over the first
  /// LcpParams::coarse_fraction of the model (their head, an unbiased subsample), are scored in
  /// full; the base's best is the best of them. Planar and symmetric bases give dozens of
  /// near-equal sliding fits, which otherwise survive the coarse checks for most of the model.
  int finished_per_base = 4;
  LcpParams lcp;
  IcpParams icp;
  FreeSpaceParams free_space;
  int bases = 100;  ///< bases per object (at most, with consensus_bases)
  /// Base draws per object when fewer bases are asked for: a base that gives nothing to verify
  /// (no congruent set on the model, or no set whose fit passes) is drawn again, up to
  /// max(1, base_draw_budget / bases) draws in all. On a cluttered segment most draws straddle
  /// other surfaces, so a few bases would otherwise mean fewer verified ones; with `bases` at or
  /// above the budget every base is drawn once, as in the paper.
  int base_draw_budget = 100;
  /// The first this many bases of an object (one consensus block) draw their points by
  /// pi_k^focus_exponent (BaseWeighting::kFocused), the others by pi_k as the paper does. On a
  /// network's graded map focused bases lie on the object more often, so few bases suffice. They
  /// also crowd onto the map's most confident part; the later bases keep the paper's spread over
  /// the segment, which flat maps (simulated ones) need to cover the object.
  int focused_bases = 10;
  /// Adaptive stop (BaseConsensus; 0: always run `bases`, as the paper does): the bases run in
  /// blocks of kConsensusBlock, and after each block the loop ends once this many best bases so
  /// far all put the object in the same place, up to its symmetries (ADD-S below
  /// instance_separation of the diameter) and, given a free-space check, the best one keeps its
  /// surface out of free space. For a single instance only: with instances > 1 every base runs,
  /// since the next instance may come from any of them. An object in plain view reaches
  /// consensus long before `bases`, and the later bases would only confirm it.
  int consensus_bases = 8;
  static constexpr int kConsensusBlock = 10;
  /// Distinct poses to return per object (a bin of identical objects); 1 returns the best only.
  int instances = 1;
  /// Two poses are one instance when their ADD-S distance is below this fraction of the diameter
  /// (the success threshold of the evaluation, so symmetric look-alikes merge).
  float instance_separation = 0.1f;
  /// Each pose is judged against the model's shape alternatives (a mug turned about its body, a
  /// box by a half turn: findShapeAlternatives) on what tells them apart, and the best kept.
  bool shape_alternatives = true;
  double time_budget = 0;  ///< seconds per object; 0: no limit
  uint64_t seed = 0;
  int threads = 0;  ///< 0: all cores

  /// Key, range, unit and meaning of every field (docs/parameters.md).
  static const ParamSet<StocsParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
};

class StocsEstimator {
 public:
  StocsEstimator(const PreparedModel& model, const StocsParams& params);
  /// The estimator keeps a reference to the model (stocs::Estimator shares models instead): a
  /// temporary would dangle.
  StocsEstimator(PreparedModel&&, const StocsParams&) = delete;

  /// Algorithm 1 on `segment`: the object's best pose and further instances (StocsParams::
  /// instances), unjudged. With `free_space` (the frame's organized cloud), the refined candidates
  /// compete by their objective times (1 - FreeSpaceCheck::violation): of poses that explain the
  /// segment alike, the one that puts no surface where the sensor sees through wins. Reported
  /// scores stay the objective's. With StocsParams::shape_alternatives, each pose is then judged
  /// against its shape alternatives on the segment and `evidence` (alternative_choice.h).
  PoseEstimate search(const SoftSegment& segment, const FreeSpaceCheck* free_space = nullptr,
                      const FrameEvidence& evidence = {}) const;

  const StocsParams& params() const { return params_; }

 private:
  /// Candidates for refinement: the best bases' poses.
  size_t refinedBases() const;
  /// Base scores each thread keeps for its pruning bound (BaseStages::keep).
  size_t keptScores() const;
  /// The anytime loop over the bases on `threads` threads (the base loop of Algorithm 1), with
  /// early refinement of finished bases; every base's outcome, cleared past a consensus stop.
  std::vector<BaseOutcome> runBases(const SoftSegment& segment, const LcpScorer& scorer,
                                    const FreeSpaceCheck* free_space,
                                    const RefinementContext& refinement, EarlyRefinements& early,
                                    int threads, std::chrono::steady_clock::time_point start) const;

  const PreparedModel& model_;
  StocsParams params_;
  CongruentSetMatcher matcher_;
  PoseProximity proximity_;
};

}  // namespace stocs
