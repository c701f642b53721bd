#include <algorithm>
#include <cmath>

#include "stocs/geometry/mesh.h"

namespace stocs {

float pointSetDiameter(const std::vector<Eigen::Vector3f>& points) {
  if (points.size() < 2) return 0;
  // The two endpoints of the diameter are extreme along the direction joining them, so the extremes
  // along many directions contain them or points within a tiny relative distance of them.
  constexpr int kDirections = 256;
  std::vector<size_t> candidates;
  const float golden = static_cast<float>(M_PI * (3.0 - std::sqrt(5.0)));
  for (int d = 0; d < kDirections; ++d) {
    const float z = 1.0f - 2.0f * (d + 0.5f) / kDirections;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const Eigen::Vector3f dir(r * std::cos(golden * d), r * std::sin(golden * d), z);
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
