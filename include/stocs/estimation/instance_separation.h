#pragma once
// Whether two poses of one object put it in the same place, up to the object's symmetries: the
// ADD-S distance between them (mean distance from each model point under one pose to the closest
// model point under the other) is below a threshold. ADD-S forgives every symmetry of the shape,
// so the poses of a symmetric object that look alike count as one instance without a symmetry
// list. Used for the non-maximum suppression of multi-instance output.

#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "stocs/model/object_model.h"

namespace stocs {

class InstanceSeparation {
 public:
  /// `threshold` in metres. At most `max_points` model points (an even subsample) are compared.
  InstanceSeparation(const ObjectModel& model, float threshold, size_t max_points = 256);
  ~InstanceSeparation();

  bool samePlace(const Eigen::Isometry3f& a, const Eigen::Isometry3f& b) const;

 private:
  struct Index;
  std::unique_ptr<Index> index_;  // kd-tree over all model points (pimpl: nanoflann stays private)
  std::vector<Eigen::Vector3f> probe_;
  float threshold_;
};

}  // namespace stocs
