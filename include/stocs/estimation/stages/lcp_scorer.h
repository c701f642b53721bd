#pragma once
// Stage 4 of StoCS: verification by the paper's alignment objective
//   f(m_i, T, S_k) = pi_k(s*) if |T(m_i) - s*| < delta_s and T(N(m_i)) . N(s*) > cos(delta_n), else
//   0
// summed over the model points, where s* is the segment point closest to T(m_i).
// With instance regions, the segment of a hypothesis is the region its base was drawn from: s* is
// searched among that region's points only.

#include <Eigen/Geometry>
#include <limits>

#include "stocs/estimation/stages/region_grids.h"
#include "stocs/estimation/stages/soft_segment.h"
#include "stocs/model/object_model.h"
#include "stocs/util/param_set.h"

namespace stocs {

struct LcpParams {
  float distance = 0.005f;         ///< delta_s, metres
  float normal_angle_deg = 30.0f;  ///< delta_n as an angle: normals must agree within it
  /// Coarse-to-fine verification: after this fraction of the model points (in whole chunks of
  /// 16), and again after every further such fraction, a hypothesis whose score extrapolated to all
  /// of them is too far below the score it must reach is dropped: by 1 - `coarse_ratio` of it at
  /// the first check, by less at later ones as the sample grows (see LcpScorer::advance). Model
  /// samples are stored in random order, so the points seen are an unbiased subsample. 0 disables
  /// it (then only the exact bound stops early).
  float coarse_fraction = 0.125f;
  float coarse_ratio = 0.5f;

  /// Key, range, unit and meaning of every field (docs/parameters.md).
  static const ParamSet<LcpParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
};

struct LcpDetail {
  float score = 0;            ///< the objective: sum of pi_k(s*) over matched model points
  int matched = 0;            ///< model points that contributed
  int facing = 0;             ///< model points whose transformed normal faces the camera
  float mean_confidence = 0;  ///< mean network probability of the matched segment points
};

/// The objective over the first model points of a hypothesis (LcpScorer::extendHead), to be
/// finished by LcpScorer::finishScore.
struct PartialScore {
  float total = 0;    ///< objective over the points seen
  uint32_t seen = 0;  ///< model points seen (in model order)
};

class LcpScorer {
 public:
  LcpScorer(const SoftSegment& segment, const LcpParams& params);
  /// The scorer keeps a reference to the segment: a temporary would dangle.
  LcpScorer(SoftSegment&&, const LcpParams&) = delete;

  /// The objective for `pose` (model to camera) against the points of `region` (-1: all points).
  /// Returns a negative value, having stopped early, when the remaining model points cannot lift
  /// the score to `must_reach` (exact), or when the coarse check of LcpParams finds the hypothesis
  /// far below it (a heuristic: see coarse_fraction).
  float score(const ObjectModel& model, const Eigen::Isometry3f& pose, int region = -1,
              float must_reach = -std::numeric_limits<float>::infinity()) const;

  /// Verification in steps, to rank the hypotheses of a base before finishing any: extendHead
  /// continues `partial` without early stop up to `share` (0 to 1) of the head, the first
  /// coarse_fraction of the model points (all of them when it is 0), in whole chunks; finishScore
  /// scores the rest as score() does, with the coarse checks and the early stop against
  /// `must_reach`. Extending an empty PartialScore to the whole head and finishing it is score()
  /// with the same must_reach.
  void extendHead(const ObjectModel& model, const Eigen::Isometry3f& pose, int region,
                  PartialScore& partial, float share) const;
  float finishScore(const ObjectModel& model, const Eigen::Isometry3f& pose, int region,
                    PartialScore head,
                    float must_reach = -std::numeric_limits<float>::infinity()) const;

  /// The objective's normal test: a model normal (in the camera frame) and a scene normal agree
  /// when they are within delta_n.
  bool normalsAgree(const Eigen::Vector3f& model_normal,
                    const Eigen::Vector3f& scene_normal) const {
    return model_normal.dot(scene_normal) > cos_normal_;
  }

  /// The objective with its parts (no early stop).
  LcpDetail detail(const ObjectModel& model, const Eigen::Isometry3f& pose, int region = -1) const;

  /// Index of the segment point of `region` (-1: any) closest to p within delta_s, or -1.
  int closest(const Eigen::Vector3f& p, int region) const { return grids_.of(region).closest(p); }

  const SoftSegment& segment() const { return segment_; }
  const LcpParams& params() const { return params_; }

 private:
  const SoftSegment& segment_;
  LcpParams params_;
  static constexpr uint32_t kChunk = 16;  // model points per step of the facing test and checks
  /// Model points seen at the first coarse check (whole chunks).
  uint32_t headSize(size_t model_points) const;
  /// Continues `partial` over model points [partial.seen, end); false on an early stop.
  bool advance(const ObjectModel& model, const Eigen::Isometry3f& pose, int region,
               PartialScore& partial, uint32_t end, float must_reach) const;

  RegionGrids grids_;  // at delta_s
  float cos_normal_;
  float sin_normal_;  // bound of n.v for a model point that can still match (see score())
  float max_probability_ = 0;
};

}  // namespace stocs
