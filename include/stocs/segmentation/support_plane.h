#pragma once
// The plane an object rests on (a table, a shelf, a bin's floor), fitted to the measured surface
// around it. Turns of an object that its visible shape cannot tell apart can differ in where its
// underside lies: a long box's quarter turn about its length, seen from above, floats over the
// table by the difference of its sides.

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace stocs {

struct Plane {
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();  ///< unit, towards the camera
  float offset = 0;

  /// Signed distance of `p` (camera frame), positive on the camera's side.
  float distance(const Eigen::Vector3f& p) const { return normal.dot(p) + offset; }
};

/// The plane that most of `points` (camera frame, metres; the camera at the origin) lie on within
/// `tolerance`, by RANSAC and a least-squares refit to its inliers (PCL), facing the camera; none
/// when fewer than `min_inliers` points lie on any.
std::optional<Plane> dominantPlane(const std::vector<Eigen::Vector3f>& points, float tolerance,
                                   size_t min_inliers);

}  // namespace stocs
