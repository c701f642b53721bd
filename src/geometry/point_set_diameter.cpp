#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "stocs/geometry/mesh.h"

namespace stocs {
namespace {

constexpr int kDirections = 256;

/// Direction d of kDirections spread evenly over the sphere (a Fibonacci lattice).
Eigen::Vector3f sphereDirection(int d) {
  const float golden = static_cast<float>(M_PI * (3.0 - std::sqrt(5.0)));
  const float z = 1.0f - 2.0f * (d + 0.5f) / kDirections;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {r * std::cos(golden * d), r * std::sin(golden * d), z};
}

}  // namespace

/// Extent of the points along a unit direction.
float widthAlong(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f& dir) {
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (const Eigen::Vector3f& p : points) {
    lo = std::min(lo, p.dot(dir));
    hi = std::max(hi, p.dot(dir));
  }
  return hi - lo;
}

float pointSetMinWidth(const std::vector<Eigen::Vector3f>& points) {
  if (points.size() < 2) return 0;
  Eigen::Vector3f best_dir = sphereDirection(0);
  float best = widthAlong(points, best_dir);
  for (int d = 1; d < kDirections; ++d) {
    const float w = widthAlong(points, sphereDirection(d));
    if (w < best) std::tie(best, best_dir) = std::make_pair(w, sphereDirection(d));
  }
  // The lattice's directions lie about 13 degrees apart: steps of half that, halved each round,
  // toward any of 8 neighbours in the tangent plane that is thinner.
  for (float step = 0.11f; step > 0.002f; step *= 0.5f) {
    const Eigen::Vector3f a = best_dir.unitOrthogonal(), b = best_dir.cross(a);
    const Eigen::Vector3f centre = best_dir;
    for (int k = 0; k < 8; ++k) {
      const float angle = static_cast<float>(M_PI) * k / 4;
      const Eigen::Vector3f dir =
          (centre + step * (std::cos(angle) * a + std::sin(angle) * b)).normalized();
      const float w = widthAlong(points, dir);
      if (w < best) std::tie(best, best_dir) = std::make_pair(w, dir);
    }
  }
  return best;
}

float pointSetDiameter(const std::vector<Eigen::Vector3f>& points) {
  if (points.size() < 2) return 0;
  // The two endpoints of the diameter are extreme along the direction joining them, so the extremes
  // along many directions contain them or points within a tiny relative distance of them.
  std::vector<size_t> candidates;
  for (int d = 0; d < kDirections; ++d) {
    const Eigen::Vector3f dir = sphereDirection(d);
    size_t lo = 0, hi = 0;
    for (size_t i = 1; i < points.size(); ++i) {
      const float s = points[i].dot(dir);
      if (s < points[lo].dot(dir)) lo = i;
      if (s > points[hi].dot(dir)) hi = i;
    }
    candidates.push_back(lo);
    candidates.push_back(hi);
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  float best = 0;
  for (size_t a = 0; a < candidates.size(); ++a) {
    for (size_t b = a + 1; b < candidates.size(); ++b) {
      best = std::max(best, (points[candidates[a]] - points[candidates[b]]).squaredNorm());
    }
  }
  return std::sqrt(best);
}

}  // namespace stocs
