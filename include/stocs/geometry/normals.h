#pragma once
// Surface normals for scene and model points.
//
// Scene: PCA over the organized neighbourhood of a pixel within a metric radius, oriented toward
// the camera. Computed only for the pixels asked for (the segment), so the cost follows the segment
// size, not the image size as with PCL's integral-image estimator, and depth edges do not blur the
// result because neighbours beyond the radius are left out.
//
// Model: PCA over the k nearest neighbours, then oriented outward by visibility: a point seen from
// a viewpoint on a sphere around the object must face that viewpoint. This is right for concave
// shapes (the inside of a bowl is seen from above its rim and faces up), where flipping away from
// the centroid is wrong.

#include <Eigen/Core>
#include <vector>

#include "stocs/geometry/organized_cloud.h"
#include "stocs/util/param_set.h"

namespace stocs {

struct OrganizedNormalParams {
  /// Metres; neighbours farther than this from the centre pixel are ignored. Far from the camera it
  /// grows to 2.5 pixel footprints so that a normal always has neighbours to rest on.
  float radius = 0.01f;
  int samples_per_axis = 9;  ///< at most this many window samples per image axis (a stride)
  int min_neighbours = 6;    ///< fewer valid neighbours give no normal

  /// Key, range, unit and meaning of every field (docs/parameters.md).
  static const ParamSet<OrganizedNormalParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
};

/// Normal at pixel `index` of `cloud`, seen by a camera with focal length `focal_px` (pixels), or a
/// NaN vector when the neighbourhood is too sparse or degenerate.
Eigen::Vector3f organizedNormal(const OrganizedCloud& cloud, int index, float focal_px,
                                const OrganizedNormalParams& params);

/// Unoriented unit normals by PCA over the k nearest neighbours (k >= 3) of each point.
std::vector<Eigen::Vector3f> estimatePcaNormals(const std::vector<Eigen::Vector3f>& points, int k);

struct VisibilityOrientationParams {
  int viewpoints = 96;     ///< viewpoints evenly spread on a sphere around the object
  float splat_radius = 0;  ///< z-buffer footprint of a point, metres (0: from the point spacing)
};

/// Flips each normal to face outward by visibility voting (see the file comment). Points seen from
/// no viewpoint (deep cavities) take the orientation of their nearest voted neighbour. Returns the
/// number of normals that were flipped.
int orientNormalsByVisibility(const std::vector<Eigen::Vector3f>& points,
                              std::vector<Eigen::Vector3f>& normals,
                              const VisibilityOrientationParams& params = {});

/// Median distance from a point to its nearest other point (repeated points count once); 0 when
/// there are fewer than two distinct points.
float medianSpacing(const std::vector<Eigen::Vector3f>& points);

}  // namespace stocs
