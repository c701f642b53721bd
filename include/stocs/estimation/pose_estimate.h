#pragma once
// What the estimation of one object gives, from the StoCS search up to the node's message: the
// pose, further instances, their confidence and what the search took. One type for every layer
// and every method (PoseMethod).

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "stocs/estimation/stages/lcp_scorer.h"
#include "stocs/estimation/stages/pose_confidence.h"
#include "stocs/model/near_symmetries.h"

namespace stocs {

/// Seconds spent in each stage, summed over threads (the paper's Table 1c breakdown).
struct StageSeconds {
  double segment = 0;  ///< the soft segment (detectObject)
  double sampling = 0;
  double matching = 0;
  double verification = 0;  ///< rigid fits and scoring
  double refinement = 0;
};

/// One distinct pose of the object.
struct InstancePose {
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();  ///< model to camera
  /// The method's score of the pose, higher is better: StoCS's is the alignment objective
  /// (lcp.score), a baseline's its own fitness.
  float score = 0;
  LcpDetail lcp;         ///< the alignment objective in detail (StoCS only)
  bool refined = false;  ///< ICP moved the pose and did not lower the objective
  int region = -1;       ///< instance region the pose was found in (-1: no regions)
  /// Probability that the pose is right (ADD-S below 10% of the object's diameter), calibrated on
  /// labelled estimates; comparable across objects, scenes and segment sizes (StoCS only).
  float confidence = 0;
  ConfidenceEvidence evidence;  ///< what the confidence is computed from (StoCS only)
  /// The pose may be acted on: its confidence reaches the configured minimum. A rejected pose is
  /// kept for evaluation, but neither published nor written to results.
  bool accepted = true;
  std::string rejection;  ///< why the pose was not accepted (empty when accepted)
  /// Covariance of the pose's error in the camera frame: x, y, z in metres, then rotation about
  /// x, y and z in radians (REP 103 order, as geometry_msgs/PoseWithCovariance). Zero where the
  /// method gives none.
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
  /// The model's shape alternatives that fit the data as well as `pose` (nothing seen tells them
  /// apart, e.g. a mug whose handle is hidden): the object may as well be at pose * motion. The
  /// covariance spans them. Empty: the pose is told apart from every alternative (StoCS only).
  std::vector<ShapeAlternative> ambiguous;
};

/// What the estimation of one object gives: its distinct poses with their objective, and what it
/// took. Every method returns it (PoseMethod), StoCS fills every field.
struct PoseEstimate {
  /// Distinct poses, best first (by objective, then as the near-symmetry choice and the declared
  /// symmetries settle them), at most StocsParams::instances. The first is the object's pose: the
  /// one pose every output reports.
  std::vector<InstancePose> instances;
  /// The best pose of each base that found one, best objective first (StoCS only): the consensus
  /// evidence of a pose found otherwise (a followed one) is counted among them.
  std::vector<Eigen::Isometry3f> base_poses;
  size_t segment_points = 0;   ///< points of the segment the method registered against
  int bases_tried = 0;         ///< bases started within the budget and before consensus
  int bases_sampled = 0;       ///< of those, bases actually drawn
  int base_draws = 0;          ///< draws in all, with those of bases drawn again (base_draw_budget)
  int bases_with_sets = 0;     ///< of those, bases with at least one congruent set
  long congruent_sets = 0;     ///< sets verified (after the per-base cap)
  long hypotheses = 0;         ///< rigid fits that passed the RMS check and were scored
  long duplicates = 0;         ///< rigid fits skipped as near-duplicates of a scored one
  long normal_mismatches = 0;  ///< rigid fits skipped by StocsParams::min_normal_agreement
  long finished = 0;   ///< hypotheses scored beyond their head (StocsParams::finished_per_base)
  long icp_steps = 0;  ///< ICP steps taken by all refined candidates
  StageSeconds stages;
  /// Wall time: StocsEstimator::search alone, or with the soft segment (detectObject) or the
  /// method's own steps (PoseMethod).
  double seconds = 0;

  /// There is a pose: `instances` is not empty.
  bool found() const { return !instances.empty(); }
  /// The object's pose (the first instance); only when found().
  const InstancePose& best() const { return instances.front(); }
  InstancePose& best() { return instances.front(); }
};

}  // namespace stocs
