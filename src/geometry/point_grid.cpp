#include "stocs/geometry/point_grid.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace stocs {
namespace {

/// Cells allowed per point before the cells grow (DenseCells::cover).
constexpr size_t kCellsPerPoint = 8;

}  // namespace

void PointGrid::assign(const std::vector<Eigen::Vector3f>& points, float cell_size) {
  if (!(cell_size > 0)) throw std::invalid_argument("PointGrid cell size must be positive");
  points_.clear();
  index_.clear();
  if (points.empty()) {
    cells_ = DenseCells{};
    cells_.size = cell_size;
    return;
  }
  // The grid is rebuilt for every base of the congruent-set search, so the passes below are
  // written for the compiler: plain loops, cheaper than Eigen's per-point allFinite, cwiseMin and
  // cwiseMax. A NaN would slip through the bounding box (comparisons ignore it) into a cell, hence
  // the finiteness pass, over all coordinates as one float array (vectorized).
  static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "points must be packed floats");
  const float* coordinates = points.front().data();
  int not_finite = 0;
  for (size_t i = 0; i < 3 * points.size(); ++i) {
    not_finite |= !(std::abs(coordinates[i]) <= std::numeric_limits<float>::max());
  }
  if (not_finite) throw std::invalid_argument("PointGrid points must be finite");
  float lx = points.front().x(), ly = points.front().y(), lz = points.front().z();
  float hx = lx, hy = ly, hz = lz;
  for (const Eigen::Vector3f& p : points) {
    lx = std::min(lx, p.x());
    ly = std::min(ly, p.y());
    lz = std::min(lz, p.z());
    hx = std::max(hx, p.x());
    hy = std::max(hy, p.y());
    hz = std::max(hz, p.z());
  }
  const Eigen::Vector3f lo(lx, ly, lz);
  cells_ =
      DenseCells::cover(lo, Eigen::Vector3f(hx, hy, hz) - lo, cell_size,
                        static_cast<double>(std::max<size_t>(64, kCellsPerPoint * points.size())));
  // Each point's cell once, for both passes of the sort. From a local copy of the layout: the
  // stores to cell_ (size_t) could alias its dims, which the compiler would then reload.
  const DenseCells cells = cells_;
  cell_.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    size_t c[3];
    for (int a = 0; a < 3; ++a) {
      // The bounding box's far faces can round onto one cell past the last.
      // Through uint32_t: a float to size_t conversion costs a compare and a branch on x86-64.
      c[a] =
          std::min<size_t>(static_cast<uint32_t>((points[i][a] - cells.origin[a]) * cells.inv_size),
                           cells.dims[a] - 1);
    }
    cell_[i] = cells.index(c[0], c[1], c[2]);
  }
  sortIntoCells(
      cells_.count(), static_cast<uint32_t>(points.size()),
      [&](uint32_t i, auto&& emit) { emit(cell_[i]); }, start_, index_);
  points_.resize(points.size());
  for (size_t k = 0; k < index_.size(); ++k) points_[k] = points[index_[k]];
}

int PointGrid::closestWithin(const Eigen::Vector3f& q, float radius, float* distance_sq) const {
  int best = -1;
  float best_d2 = radius * radius;
  forEachWithin(q, radius, [&](int index, float d2) {
    if (d2 < best_d2 || (d2 == best_d2 && best >= 0 && index < best)) {
      best = index;
      best_d2 = d2;
    }
  });
  if (distance_sq && best >= 0) *distance_sq = best_d2;
  return best;
}

}  // namespace stocs
