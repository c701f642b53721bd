#pragma once
// Rotations that almost map an object onto itself: a 180 x 45 x 50 mm box turned a quarter about
// its long axis moves its surface by 2.5 mm, less than the sample spacing, so the objective and
// the refinement often settle on either, and the evaluation (ADD-S) counts both right. An exact
// symmetry (a turn that moves no surface) is left out: a pose's covariance is of the error to the
// nearest symmetric equivalent. The pose covariance widens the rotation about a near symmetry's
// axis so that the other pose lies inside its ellipsoids (pose_covariance.h).

#include <Eigen/Core>
#include <vector>

#include "stocs/model/object_model.h"

namespace stocs {

struct NearSymmetry {
  Eigen::Vector3f axis;  ///< unit, model frame, through the samples' centre
  float angle = 0;       ///< radians in (0, pi]: the turn's smallest angle
  /// Metres: how far the turn moves the surface on average (turnedSurfaceDistance); a pose that
  /// settles on the turn is off by about as much in position.
  float shift = 0;
};

/// Turns by a quarter and a half about the samples' principal axes whose mean
/// point-to-plane distance of the turned samples to the model's samples (normals within 30
/// degrees; other samples count the sampling radius) lies between 10% and 100% of the sampling
/// radius. Deterministic.
std::vector<NearSymmetry> findNearSymmetries(const ObjectModel& model);

/// Mean distance of the samples turned by `angle` about `axis` through their centre to the model's
/// surface, as findNearSymmetries measures it (metres).
float turnedSurfaceDistance(const ObjectModel& model, const Eigen::Vector3f& axis, float angle);

}  // namespace stocs
