#pragma once
// Optional last stage: point-to-plane ICP of the best pose on the soft segment. Written here rather
// than taken from PCL because it weights residuals by the segment's network probability, uses only
// model points facing the camera, and searches correspondences in the pose's instance region.

#include <Eigen/Geometry>

#include "stocs/estimation/stages/lcp_scorer.h"
#include "stocs/estimation/stages/region_grids.h"
#include "stocs/util/param_set.h"

namespace stocs {

struct IcpParams {
  bool enabled = true;
  /// The poses of this many best bases are refined and the best objective after refinement wins.
  int candidates = 10;
  /// Steps at most. Most refinements do not converge but slide along near-symmetries a little
  /// every step, so further steps rarely change which pose wins.
  int iterations = 14;
  /// Screening of the candidates: each first takes this many steps, and only the `finalists` best
  /// of them by objective take the rest. 0 (or iterations or more) refines every candidate fully,
  /// as do several instances per object (every candidate may be one).
  int screening_iterations = 8;
  int finalists = 2;
  float max_distance = 0.01f;      ///< correspondence radius, metres
  float normal_angle_deg = 45.0f;  ///< correspondences need normals within this angle

  /// Key, range, unit and meaning of every field (docs/parameters.md).
  static const ParamSet<IcpParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
};

/// A refinement in progress: run it on with IcpRefiner::iterate.
struct IcpRun {
  Eigen::Isometry3f pose;         ///< the current pose
  Eigen::Isometry3f before_last;  ///< the pose two steps back, for the cycle test
  int iterations = 0;             ///< steps taken
  bool finished = false;          ///< converged, cycling, or too few correspondences

  explicit IcpRun(const Eigen::Isometry3f& start) : pose(start), before_last(start) {}
};

/// The weighted point-to-plane normal equations of a pose: one row per camera-facing model point
/// with a correspondence, Jacobian [(p - c) x n, n] of the residual n.(p - s) with respect to a
/// small rotation w about `centre` (the posed model's centre) followed by a translation v, each
/// row weighted by the network confidence of its segment point.
struct PointToPlaneSystem {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();                       ///< camera frame, metres
  Eigen::Matrix<double, 6, 6> jtj = Eigen::Matrix<double, 6, 6>::Zero();  ///< (w, v) order
  Eigen::Matrix<double, 6, 1> jtr = Eigen::Matrix<double, 6, 1>::Zero();
  double weighted_squares = 0;  ///< sum of weight x residual^2, m^2
  int used = 0;                 ///< correspondences
};

/// Refines poses against one segment; the correspondence grids are built once for all of them.
class IcpRefiner {
 public:
  /// Throws InputError when `params` are out of range.
  IcpRefiner(const SoftSegment& segment, const IcpParams& params);
  /// The refiner keeps a reference to the segment: a temporary would dangle.
  IcpRefiner(SoftSegment&&, const IcpParams&) = delete;

  /// Refined pose against the segment points of `region` (-1: all), or `pose` itself when fewer
  /// than 6 correspondences are found. `near`, a scorer of the same segment, speeds up the search
  /// without changing it: its delta_s grid lists fewer points per cell, and the closest point
  /// within delta_s, where there is one, is the closest within the correspondence radius too. It is
  /// ignored when its delta_s exceeds that radius.
  Eigen::Isometry3f refine(const ObjectModel& model, const Eigen::Isometry3f& pose, int region,
                           const LcpScorer* near = nullptr) const;

  /// Runs `run` on to `until` steps in all (at most the iterations of IcpParams) unless it
  /// finishes first; refine() is one call of it to the end. Running on in several calls takes the
  /// same steps as one call.
  void iterate(const ObjectModel& model, IcpRun& run, int until, int region,
               const LcpScorer* near = nullptr) const;

  /// The normal equations at `pose` against the segment points of `region` (-1: all); `near` as
  /// in refine(). One pass over the model's correspondences.
  PointToPlaneSystem system(const ObjectModel& model, const Eigen::Isometry3f& pose, int region,
                            const LcpScorer* near = nullptr) const;

  const IcpParams& params() const { return params_; }

 private:
  const SoftSegment& segment_;
  IcpParams params_;
  RegionGrids grids_;  // at the correspondence radius
  float cos_normal_;
};

/// One refinement without keeping the grid: IcpRefiner(segment, params).refine(model, pose,
/// region).
Eigen::Isometry3f refinePointToPlane(const ObjectModel& model, const SoftSegment& segment,
                                     const Eigen::Isometry3f& pose, int region,
                                     const IcpParams& params);

}  // namespace stocs
