#pragma once
// A cheap bound on how far a change of pose moves an object: the largest displacement of any point
// of the model's bounding sphere. The estimator uses it to skip scoring a hypothesis that nearly
// repeats one already scored for the same base (congruent sets that differ by a neighbouring model
// sample give poses a millimetre or two apart, and a box yields hundreds of them).

#include <Eigen/Geometry>

#include "stocs/model/object_model.h"

namespace stocs {

class PoseProximity {
 public:
  explicit PoseProximity(const ObjectModel& model);

  /// Whether an upper bound of max |a m - b m| over the model points m is below `distance`
  /// (metres): then no model point moves that far between the two poses.
  bool within(const Eigen::Isometry3f& a, const Eigen::Isometry3f& b, float distance) const {
    // a m - b m = dR (m - c) + (dR c + dt) with dR = Ra - Rb, dt = ta - tb, |m - c| <= radius, and
    // the Frobenius norm bounds the spectral norm of dR.
    const Eigen::Matrix3f dr = a.linear() - b.linear();
    const float centre_move = (dr * centre_ + a.translation() - b.translation()).norm();
    return centre_move < distance && centre_move + dr.norm() * radius_ < distance;
  }

  /// The point whose move is the first term of the bound: when it moves by the distance or more,
  /// within() is false, which callers can test first with cached images of the centre.
  const Eigen::Vector3f& centre() const { return centre_; }
  /// The radius of the sphere about centre() that holds every model point (metres).
  float radius() const { return radius_; }

 private:
  Eigen::Vector3f centre_ = Eigen::Vector3f::Zero();  // of the model points' bounding box
  float radius_ = 0;                                  // of the sphere about centre_ holding them
};

}  // namespace stocs
