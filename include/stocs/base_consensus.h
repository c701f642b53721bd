#pragma once
// An adaptive end to the base loop. The paper runs a fixed number of bases (or a time budget),
// sized for the hardest segments; on an object in plain view many bases land on the same pose
// long before that, and the rest only confirm it. BaseConsensus watches the best bases so far and
// says when the N best of them all put the object in the same place, up to the object's
// symmetries (InstanceSeparation's ADD-S test): independent random bases that agree are the
// classic RANSAC sign that more samples will rarely change the answer. Rarely is not never (a pose
// that only a late base finds, or one that the free-space check prefers among more candidates, is
// lost): the accuracy it costs is measured in BENCHMARKS.md, which is why the estimator leaves it
// off by default.

#include <Eigen/Geometry>
#include <vector>

#include "stocs/instance_separation.h"
#include "stocs/object_model.h"

namespace stocs {

class BaseConsensus {
 public:
  /// Consensus is the `needed` best bases all within `separation` metres ADD-S of the best one.
  BaseConsensus(const ObjectModel& model, float separation, int needed);

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
  size_t needed_;
  std::vector<Entry> best_;  // best first, at most needed_
};

}  // namespace stocs
