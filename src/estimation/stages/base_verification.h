#pragma once
// One base of StoCS's loop (paper Algorithm 1, lines 3-8): draw a base on the soft segment
// (Algorithm 2), find its congruent sets on the model, fit a rigid transform to each, and verify
// the hypotheses by the alignment objective, keeping the base's best.

#include <Eigen/Geometry>
#include <array>
#include <limits>
#include <vector>

#include "stocs/estimation/pose_proximity.h"
#include "stocs/estimation/stages/base_sampler.h"
#include "stocs/estimation/stages/congruent_set_matcher.h"
#include "stocs/estimation/stages/lcp_scorer.h"
#include "stocs/estimation/stocs_estimator.h"
#include "stocs/util/random.h"

namespace stocs {

/// What one base produced: its best hypothesis and counters.
struct BaseOutcome {
  bool tried = false, sampled = false;
  int draws = 0, sets = 0;
  long hypotheses = 0, duplicates = 0, normal_mismatches = 0, finished = 0;
  float score = -std::numeric_limits<float>::infinity();
  int region = -1;  // instance region of the base, -1 without regions
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  StageSeconds stages;
};

/// What every thread's verifier reads: the stages, built once per estimate.
struct BaseStages {
  const SoftSegment& segment;
  const BaseSampler& sampler;
  const CongruentSetMatcher& matcher;
  const LcpScorer& scorer;
  const ObjectModel& model;
  const PoseProximity& proximity;
  const StocsParams& params;
  /// Base scores a thread keeps for its pruning bound: those that can still be among the ones
  /// refined (or compared by the consensus stop).
  size_t keep;
};

/// Runs bases for one thread, with the thread's scratch memory and its best base scores so far.
class BaseVerifier {
 public:
  explicit BaseVerifier(const BaseStages& stages) : s_(stages) {}

  /// Runs base `b` into `out`: its draws from its own random stream, then the verification of
  /// their hypotheses.
  void run(int b, BaseOutcome& out);

 private:
  /// A hypothesis with the image of the model's centre under it.
  struct PlacedPose {
    Eigen::Isometry3f pose;
    Eigen::Vector3f centre;
  };

  /// One draw of a base and its hypotheses (appended to `scored_`); false when no base could be
  /// drawn.
  bool draw(Rng& rng, BaseWeighting weighting, BaseOutcome& out);
  /// The hypotheses of `fit` that pass the normal and duplicate checks, into `scored_`.
  void keepHypotheses(const std::array<Eigen::Vector3f, 4>& points,
                      const std::array<Eigen::Vector3f, 4>& normals, BaseOutcome& out);
  /// Scores the hypotheses in `scored_` and keeps the best in `out`.
  void verify(BaseOutcome& out);
  /// Scores the heads of the hypotheses in rounds and leaves in `order_` those to finish.
  void rankHeads(const BaseOutcome& out);
  /// True when `pose` moves no model point farther than duplicate_distance from one of `scored_`.
  bool isNearDuplicate(const PlacedPose& pose) const;
  /// True when enough base normals agree with their model normals under `pose`, by the
  /// objective's normal test (StocsParams::min_normal_agreement).
  bool normalsAgree(const Eigen::Isometry3f& pose, const CongruentSet& set,
                    const std::array<Eigen::Vector3f, 4>& base_normals) const;

  const BaseStages& s_;
  /// Best base scores of this thread (ascending, at most `keep`): scores below the K-th of them
  /// cannot be among the K best overall, so verification may stop early on them.
  std::vector<float> thread_top_;
  BaseSamplingScratch sampling_;
  std::vector<CongruentSet> sets_;
  CongruentSetMatcher::Workspace matching_;
  std::vector<PlacedPose> scored_;   // hypotheses of the current base
  std::vector<PartialScore> heads_;  // their objectives over the first model points
  std::vector<uint32_t> order_;      // the order in which they are finished
};

}  // namespace stocs
