#pragma once
// Stage 2 of StoCS: the 4-point sets on the model congruent to a base.
//
// The base is split into two pairs (a, b), (c, d), choosing the split whose lines cross most
// squarely inside both segments. The closest points of the two lines, at ratios t on ab and u on
// cd, are invariant under rigid motion (the 4PCS invariants, without requiring exact coplanarity).
// The model pairs with the PPF of (a, b) give intermediate points m_i + t (m_j - m_i), those with
// the PPF of (c, d) give m_k + u (m_l - m_k); pairs whose intermediate points meet within the
// tolerance (plus the base's own line gap) form candidates, and a candidate is congruent when all
// six distances agree with the base's within the tolerance.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "stocs/geometry/point_grid.h"
#include "stocs/model/model_cache.h"
#include "stocs/util/param_set.h"
#include "stocs/util/random.h"

namespace stocs {

struct CongruentSetParams {
  /// Metres, on intermediate points and on each of the 6 distances. It must cover sensor noise plus
  /// the model's sampling radius (a base point's true match is up to that far from a sample).
  float tolerance = 0.01f;
  int max_sets =
      200;  ///< per base; beyond it the search stops (candidates are visited in random order)
  float min_line_angle_deg = 15.0f;  ///< bases whose best pair split crosses flatter are skipped

  /// Key, range, unit and meaning of every field (docs/parameters.md).
  static const ParamSet<CongruentSetParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
};

/// Model sample indices matched to base points 0..3.
using CongruentSet = std::array<uint16_t, 4>;

class CongruentSetMatcher {
 public:
  /// Buffers of one search, kept by the caller (one per thread) so that a search allocates
  /// nothing once they have grown.
  struct Workspace {
    std::vector<ModelPair> first, second;  // model pairs matching each base pair's PPF
    std::vector<Eigen::Vector3f> meeting;  // intermediate point of each second pair
    PointGrid grid;                        // over `meeting`
  };

  CongruentSetMatcher(const PreparedModel& model, const CongruentSetParams& params);
  /// The matcher keeps a reference to the model: a temporary would dangle.
  CongruentSetMatcher(PreparedModel&&, const CongruentSetParams&) = delete;

  /// Congruent sets for the base (points and normals in base order), at most max_sets, no
  /// duplicates, written to `out`. Returns how many were written.
  size_t find(const std::array<Eigen::Vector3f, 4>& points,
              const std::array<Eigen::Vector3f, 4>& normals, Rng& rng,
              std::vector<CongruentSet>& out, Workspace& workspace) const;
  size_t find(const std::array<Eigen::Vector3f, 4>& points,
              const std::array<Eigen::Vector3f, 4>& normals, Rng& rng,
              std::vector<CongruentSet>& out) const {
    Workspace workspace;
    return find(points, normals, rng, out, workspace);
  }

 private:
  const PreparedModel& model_;
  CongruentSetParams params_;
  float min_line_sin_;
};

}  // namespace stocs
