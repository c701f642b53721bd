#pragma once
// The last stage of StoCS: the best bases' poses refined by point-to-plane ICP, judged again by the
// objective (and the free-space check), and the distinct instances picked from them.

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "stocs/estimation/stages/free_space_check.h"
#include "stocs/estimation/stages/icp_refiner.h"
#include "stocs/estimation/stages/lcp_scorer.h"
#include "stocs/estimation/stocs_estimator.h"
#include "stocs/model/near_symmetries.h"

namespace stocs {

/// A pose with its objective, before or after refinement.
struct Hypothesis {
  Eigen::Isometry3f pose;
  float score;
  int region;
  int base;               // the base it is the best of
  bool refined = false;   // ICP moved the pose and did not lower the objective
  bool polished = false;  // refinement was tried
};

inline bool higherScore(const Hypothesis& a, const Hypothesis& b) {
  return a.score > b.score;
}

/// What refinement reads: the model, the segment's scorer and refiner (null without ICP) and the
/// frame's free-space check (null without one).
struct RefinementContext {
  const ObjectModel& model;
  const std::vector<NearSymmetry>& near_symmetries;  ///< of the model, for the covariance
  const IcpRefiner* icp;
  const LcpScorer& scorer;
  const FreeSpaceCheck* free_space;
};

/// A candidate's refinement under way: its ICP run, and the candidate judged at the run's pose.
struct Refinement {
  Hypothesis start;  // the unrefined candidate
  IcpRun run;
  std::optional<Hypothesis> judged;  // at the run's pose, once judged there

  explicit Refinement(const Hypothesis& h) : start(h), run(h.pose) {}
};

/// The steps every candidate takes before the finalists are chosen (IcpParams::
/// screening_iterations), or all of them when there is no screening: screening is off, or no more
/// than IcpParams::finalists candidates would take part.
int firstSteps(const IcpParams& icp, size_t candidates);

/// Runs `r` on to `steps` steps in all (unless it finished) and judges it there.
void refineTo(Refinement& r, int steps, const RefinementContext& context);

/// Up to `count` distinct poses from the bases' best hypotheses (`ranked`, best first). The
/// `refined_bases` best are refined first and compete by their refined objective (a 4-point
/// fit is a few mm off, and at delta_s such a right pose can score below a wrong one until it is
/// refined); then greedy non-maximum suppression: a hypothesis in the same place as one already
/// taken is skipped, and the others are refined when taken. `early`, per base, holds refinements
/// the base loop began. Adds the ICP steps taken to `steps`.
std::vector<InstancePose> selectInstances(const std::vector<Hypothesis>& ranked,
                                          size_t refined_bases, size_t count,
                                          const RefinementContext& context,
                                          float instance_separation,
                                          std::vector<std::optional<Refinement>>& early,
                                          int threads, long& steps);

}  // namespace stocs
