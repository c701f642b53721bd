#include "stocs/estimation/instance_separation.h"

#include <algorithm>
#include <stdexcept>

#include "stocs/geometry/knn_index.h"

namespace stocs {

struct InstanceSeparation::Index {
  explicit Index(const std::vector<Eigen::Vector3f>& points) : knn(points) {}
  KnnIndex knn;
};

InstanceSeparation::InstanceSeparation(const ObjectModel& model, float threshold, size_t max_points)
    : threshold_(threshold) {
  if (model.points.empty()) throw std::invalid_argument("InstanceSeparation needs model points");
  index_ = std::make_unique<Index>(model.points);
  // Model samples are stored in random order, so a prefix is an even subsample.
  probe_.assign(model.points.begin(),
                model.points.begin() + std::min(max_points, model.points.size()));
}

InstanceSeparation::~InstanceSeparation() = default;

bool InstanceSeparation::samePlace(const Eigen::Isometry3f& a, const Eigen::Isometry3f& b) const {
  // Distances in b's model frame: one kd-tree serves every pair of poses.
  const Eigen::Isometry3f a_in_b = b.inverse() * a;
  const float budget = threshold_ * static_cast<float>(probe_.size());
  std::vector<size_t> nearest;
  std::vector<float> d2;
  float sum = 0;
  for (const Eigen::Vector3f& p : probe_) {
    index_->knn.knn(a_in_b * p, 1, nearest, d2);
    sum += std::sqrt(d2.front());
    if (sum >= budget) return false;  // the mean can only grow past the threshold
  }
  return true;
}

}  // namespace stocs
