#pragma once
// Optional last stage: point-to-plane ICP of the best pose on the soft segment. Written here rather
// than taken from PCL because it weights residuals by the segment's network probability, uses only
// model points facing the camera, and searches correspondences in the pose's instance region.

#include <Eigen/Geometry>

#include "stocs/lcp_scorer.h"

namespace stocs {

struct IcpParams {
  bool enabled = true;
  /// The poses of this many best bases are refined and the best objective after refinement wins.
  int candidates = 10;
  int iterations = 20;
  float max_distance = 0.01f;      ///< correspondence radius, metres
  float normal_angle_deg = 45.0f;  ///< correspondences need normals within this angle

  /// Throws InputError naming the first value out of range.
  void validate() const;
};

/// Refined pose against the segment points of `region` (-1: all), or `pose` itself when fewer than
/// 6 correspondences are found.
Eigen::Isometry3f refinePointToPlane(const ObjectModel& model, const SoftSegment& segment,
                                     const Eigen::Isometry3f& pose, int region,
                                     const IcpParams& params);

}  // namespace stocs
