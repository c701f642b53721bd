#pragma once
// How far a change of pose moves an object's points on average (ADD between two poses): the
// tracker's test of whether a pose moves a hidden track, whose few points in view fit other poses.

#include <Eigen/Geometry>
#include <algorithm>

#include "stocs/model/object_model.h"

namespace stocs {

/// The mean distance between the model's points at `a` and at `b` (metres), over a prefix of at
/// most 256 samples: the samples are in random order, so the prefix is an unbiased subsample.
inline float meanDisplacement(const ObjectModel& model, const Eigen::Isometry3f& a,
                              const Eigen::Isometry3f& b) {
  const size_t n = std::min<size_t>(model.points.size(), 256);
  if (n == 0) return 0;
  float sum = 0;
  for (size_t i = 0; i < n; ++i) sum += (a * model.points[i] - b * model.points[i]).norm();
  return sum / static_cast<float>(n);
}

}  // namespace stocs
