#pragma once
// An adaptive end to the base loop. The paper runs a fixed number of bases (or a time budget),
// sized for the hardest segments; on an object in plain view many bases land on the same pose
// long before that, and the rest only confirm it. BaseConsensus watches the best bases so far and
// says when the N best of them all put the object in the same place, up to the object's
// symmetries (InstanceSeparation's ADD-S test): independent random bases that agree are the
// classic RANSAC sign that more samples will rarely change the answer.
//
// Agreement alone also ends the search on a wrong pose that many bases find first (a box slid
// along its face, a block turned over), so the caller may add a test of the best base's pose: the
// estimator's is the free-space check of that (unrefined) pose.

#include <Eigen/Geometry>
#include <functional>
#include <vector>

#include "stocs/estimation/instance_separation.h"
#include "stocs/model/object_model.h"

namespace stocs {

class BaseConsensus {
 public:
  /// Whether the pose of base `base`, the best so far, may end the search.
  using Accept = std::function<bool(int base)>;

  /// Consensus is the `needed` best bases all within `separation` metres ADD-S of the best one,
  /// and `accept` (when given) true for the best one.
  BaseConsensus(const ObjectModel& model, float separation, int needed, Accept accept = {});

  /// Records the best hypothesis of base `base`; a score of zero or less (no hypothesis) is
  /// ignored. Of equal scores, the lower base index ranks first, as in the estimator.
  void add(int base, float score, const Eigen::Isometry3f& pose);

  /// Whether the bases added so far have reached consensus.
  bool reached();

 private:
  struct Entry {
    float score;
    int base;
    Eigen::Isometry3f pose;
    signed char agrees;  // with the current best: -1 not yet tested, 0 no, 1 yes
  };

  InstanceSeparation same_place_;
  Accept accept_;
  size_t needed_;
  std::vector<Entry> best_;         // best first, at most needed_
  signed char best_accepted_ = -1;  // accept_ of the best: -1 not yet asked, 0 no, 1 yes
};

/// ConfidenceEvidence::consensus of `pose`: of `base_poses` (the bases' poses, best first), those
/// in the same place up to symmetries (`same_place`), at most kConsensusBases, as a share of
/// kConsensusBases. A base whose model centre (`centre`, in the model frame) lies `separation`
/// metres or more from the pose's is skipped without the ADD-S test.
float consensusShare(const Eigen::Isometry3f& pose,
                     const std::vector<Eigen::Isometry3f>& base_poses,
                     const InstanceSeparation& same_place, const Eigen::Vector3f& centre,
                     float separation);

}  // namespace stocs
