#pragma once
// Nearest-point queries within a fixed radius, for the verification inner loop. The grid covers the
// points' bounding box grown by the radius with cells of half the radius, indexed densely; each
// cell lists every point within the radius of any place in the cell, contiguously, so a query is
// one index computation and a scan of about 6 points (cells of the radius and their 27-cell
// neighbourhood would scan about 12, behind a hash probe). Building costs about 60 entries per
// point, which pays off when, as in scoring, queries outnumber points by orders of magnitude. The
// lists hold 4-byte indices into one copy of the points.

#include <Eigen/Core>
#include <vector>

#include "stocs/dense_cells.h"

namespace stocs {

class NeighbourhoodGrid {
 public:
  NeighbourhoodGrid() = default;
  NeighbourhoodGrid(const std::vector<Eigen::Vector3f>& points, float radius);
  /// Only the points whose indices are in `subset`; queries still report indices into `points`.
  NeighbourhoodGrid(const std::vector<Eigen::Vector3f>& points, const std::vector<uint32_t>& subset,
                    float radius);

  float radius() const { return radius_; }

  /// Calls visit(index, distance_sq) for every point strictly within the radius of q.
  template <class Visit>
  void forEachWithin(const Eigen::Vector3f& q, Visit&& visit) const {
    const Eigen::Vector3f c = (q - cells_.origin) * cells_.inv_size;
    // Negated comparisons also turn away NaN; the casts below are then within the grid.
    if (!(c.x() >= 0 && c.y() >= 0 && c.z() >= 0 && c.x() < dims_f_.x() && c.y() < dims_f_.y() &&
          c.z() < dims_f_.z())) {
      return;
    }
    const size_t cell = cells_.index(static_cast<size_t>(c.x()), static_cast<size_t>(c.y()),
                                     static_cast<size_t>(c.z()));
    for (uint32_t k = start_[cell], end = start_[cell + 1]; k < end; ++k) {
      const uint32_t j = lists_[k];
      const float d2 = (points_[j] - q).squaredNorm();
      if (d2 < radius2_) visit(static_cast<int>(original_[j]), d2);
    }
  }

  /// Index of the closest point strictly within the radius of q among those `accept(index)` keeps,
  /// or -1; ties go to the lower index.
  template <class Accept>
  int closest(const Eigen::Vector3f& q, Accept&& accept) const {
    int best = -1;
    float best_d2 = radius2_;
    forEachWithin(q, [&](int index, float d2) {
      if (!accept(index)) return;
      if (d2 < best_d2 || (d2 == best_d2 && index < best)) {
        best = index;
        best_d2 = d2;
      }
    });
    return best;
  }
  int closest(const Eigen::Vector3f& q) const {
    return closest(q, [](int) { return true; });
  }

 private:
  float radius_ = 0, radius2_ = 0;
  DenseCells cells_;  // over the points' bounding box grown by the radius
  Eigen::Vector3f dims_f_ =
      Eigen::Vector3f::Zero();  // cells_.dims as floats, for the bounds test of every query
  std::vector<Eigen::Vector3f> points_;  // the subset's points
  std::vector<uint32_t> original_;       // index of points_[j] in the constructor's vector
  std::vector<uint32_t> start_;          // list of cell c: lists_[start_[c] .. start_[c + 1])
  std::vector<uint32_t> lists_;          // indices into points_, concatenated
};

}  // namespace stocs
