#pragma once
// Private helper: a nanoflann kd-tree over a vector of Eigen points, for k-nearest-neighbour
// queries on models (normal estimation, spacing). nanoflann is header-only, so only the few core
// files that include this header pay its compile time.

#include <Eigen/Core>
#include <limits>
#include <nanoflann.hpp>
#include <vector>

namespace stocs {

class KnnIndex {
 public:
  explicit KnnIndex(const std::vector<Eigen::Vector3f>& points)
      : adaptor_{points}, tree_(3, adaptor_, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
    tree_.buildIndex();
  }

  /// The squared distance from q to its nearest point, or infinity for an empty set; no
  /// allocation, for queries in inner loops.
  float nearestDistanceSq(const Eigen::Vector3f& q) const {
    size_t index = 0;
    float distance_sq = std::numeric_limits<float>::infinity();
    if (!adaptor_.points.empty()) tree_.knnSearch(q.data(), 1, &index, &distance_sq);
    return distance_sq;
  }

  /// Indices of the k nearest points to q (fewer if the set is smaller), nearest first.
  void knn(const Eigen::Vector3f& q, size_t k, std::vector<size_t>& indices,
           std::vector<float>& distances_sq) const {
    k = std::min(k, adaptor_.points.size());
    indices.resize(k);
    distances_sq.resize(k);
    const size_t found = tree_.knnSearch(q.data(), k, indices.data(), distances_sq.data());
    indices.resize(found);
    distances_sq.resize(found);
  }

 private:
  struct Adaptor {
    const std::vector<Eigen::Vector3f>& points;
    size_t kdtree_get_point_count() const { return points.size(); }
    float kdtree_get_pt(size_t i, size_t dim) const { return points[i][dim]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
      return false;
    }
  };
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Adaptor>,
                                                   Adaptor, 3, size_t>;
  Adaptor adaptor_;
  Tree tree_;
};

}  // namespace stocs
