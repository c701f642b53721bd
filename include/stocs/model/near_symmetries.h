#pragma once
// Rotations that almost map an object onto itself: a 180 x 45 x 50 mm box turned a quarter about
// its long axis moves its surface by 2.5 mm, less than the sample spacing, so the objective and
// the refinement often settle on either, and the evaluation (ADD-S) counts both right. An exact
// symmetry (a turn that moves no surface) is left out: a pose's covariance is of the error to the
// nearest symmetric equivalent. The pose covariance widens the rotation about a near symmetry's
// axis so that the other pose lies inside its ellipsoids (pose_covariance.h).

#include <Eigen/Geometry>
#include <string>
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

/// A rigid motion of the model (model frame) that maps its surface nearly onto itself: a pose and
/// the pose moved by it fit the shape about equally, and only what the shape does not show (a
/// handle over free space, a hidden part seen, colour) tells them apart. A mug turned about its
/// body's axis, a box turned by a half about any axis, a can by any angle.
struct ShapeAlternative {
  Eigen::Isometry3f motion = Eigen::Isometry3f::Identity();  ///< x -> motion * x, model frame
  Eigen::Vector3f axis = Eigen::Vector3f::UnitZ();           ///< of the motion's rotation, unit
  float angle = 0;  ///< radians in (0, pi]: the rotation's angle about `axis`
  float shift = 0;  ///< metres: mean surface distance of the moved samples (as NearSymmetry)
};

/// `motion` as a shape alternative: its rotation's axis and angle filled in.
ShapeAlternative shapeAlternative(const Eigen::Isometry3f& motion, float shift);

/// Turns by multiples of 30 degrees about the samples' principal axes through their centre, kept
/// when the turned samples lie within the sampling radius of the surface on average, else aligned
/// again onto the model by a few point-to-point ICP steps (an axis off the centre, as a mug's body
/// beside its handle) and kept if they then do; then their compositions, kept the same way (at most
/// 47 in all). A kept motion turns by at least 15 degrees and is at least 15 degrees from every
/// motion kept before. Deterministic; a few tens of milliseconds.
std::vector<ShapeAlternative> findShapeAlternatives(const ObjectModel& model);

/// What `alternatives` of one pose say to a user: "fits as well turned by 90, 180 deg about model
/// axis [0.00 0.00 1.00]", one clause per axis (within 10 degrees).
std::string ambiguityText(const std::vector<ShapeAlternative>& alternatives);

/// Turns by a quarter and a half about the samples' principal axes whose mean
/// point-to-plane distance of the turned samples to the model's samples (normals within 30
/// degrees; other samples count the sampling radius) lies between 10% and 100% of the sampling
/// radius. Deterministic.
std::vector<NearSymmetry> findNearSymmetries(const ObjectModel& model);

/// Mean distance of the samples turned by `angle` about `axis` through their centre to the model's
/// surface, as findNearSymmetries measures it (metres).
float turnedSurfaceDistance(const ObjectModel& model, const Eigen::Vector3f& axis, float angle);

}  // namespace stocs
