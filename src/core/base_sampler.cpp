#include "stocs/base_sampler.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "stocs/error.h"

namespace stocs {
namespace {

/// Draws an index from (index, weight) candidates with positive weights summing to `total`.
int drawWeighted(Rng& rng, const std::vector<std::pair<int, float>>& candidates, double total) {
  const double target = uniform01(rng) * total;
  double acc = 0;
  for (const auto& [index, weight] : candidates) {
    acc += weight;
    if (acc > target) return index;
  }
  return candidates.back().first;  // rounding at the very end of the range
}

}  // namespace

void BaseSamplerParams::validate() const {
  if (!(wide_angle_deg >= 0.0f && wide_angle_deg < 90.0f)) {
    throw InputError(fmt::format("base wide angle {} deg is outside [0, 90)", wide_angle_deg));
  }
  if (!(coplanarity > 0.0f && coplanarity <= 0.1f)) {
    throw InputError(fmt::format("base coplanarity {} m is outside (0, 0.1]", coplanarity));
  }
  if (max_attempts < 1 || max_attempts > 10000) {
    throw InputError(fmt::format("base attempts {} is outside [1, 10000]", max_attempts));
  }
}

BaseSampler::BaseSampler(const SoftSegment& segment, const PpfHashMap& map,
                         const BaseSamplerParams& params)
    : segment_(segment),
      map_(map),
      params_(params),
      cos_wide_(std::cos(params.wide_angle_deg * static_cast<float>(M_PI) / 180.0f)) {
  params_.validate();
  cumulative_.reserve(segment.size());
  double acc = 0;
  for (size_t i = 0; i < segment.size(); ++i) {
    const bool on_boundary = !segment.region.empty() && segment.region[i] < 0;
    cumulative_.push_back(acc += on_boundary ? 0.0f : segment.probability[i]);
  }
}

int BaseSampler::drawFirst(Rng& rng) const {
  const double target = uniform01(rng) * cumulative_.back();
  const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), target);
  return static_cast<int>(std::min<size_t>(it - cumulative_.begin(), cumulative_.size() - 1));
}

std::optional<Base> BaseSampler::sample(Rng& rng,
                                        std::vector<std::pair<int, float>>& scratch) const {
  if (segment_.size() < 4 || !(cumulative_.back() > 0)) return std::nullopt;
  for (int attempt = 0; attempt < params_.max_attempts; ++attempt) {
    Base base{drawFirst(rng), -1, -1, -1};
    if (tryComplete(rng, base, scratch)) return base;
  }
  return std::nullopt;
}

template <class Admissible>
int BaseSampler::drawConditional(Rng& rng, Admissible&& admissible,
                                 std::vector<std::pair<int, float>>& candidates) const {
  // Rejection sampling: proposals from pi_k accepted when admissible are distributed exactly as
  // pi_k restricted to the admissible points, at the cost of a few PPF checks instead of one per
  // segment point. When admissible points are rare, the exact scan below takes over; mixing the two
  // leaves the distribution unchanged.
  constexpr int kProposals = 128;
  for (int t = 0; t < kProposals; ++t) {
    const int p = drawFirst(rng);
    if (admissible(p)) return p;
  }
  candidates.clear();
  double total = 0;
  for (int p = 0; p < static_cast<int>(segment_.size()); ++p) {
    const float w = static_cast<float>(cumulative_[p] - (p > 0 ? cumulative_[p - 1] : 0.0));
    if (w > 0 && admissible(p)) {
      candidates.emplace_back(p, w);
      total += w;
    }
  }
  return candidates.empty() ? -1 : drawWeighted(rng, candidates, total);
}

bool BaseSampler::tryComplete(Rng& rng, Base& base,
                              std::vector<std::pair<int, float>>& candidates) const {
  const auto& pts = segment_.points;
  const auto& nrm = segment_.normals;
  const bool regions = !segment_.region.empty();
  auto sameRegion = [&](int p) {
    return !regions || segment_.region[p] == segment_.region[base[0]];
  };
  auto consistentWith = [&](int p, int b) {
    return map_.consistent(pts[b], nrm[b], pts[p], nrm[p]);
  };

  // pi(p | b1) ~ pi_k(p) phi(p, b1).
  const int b1 = base[0];
  base[1] = drawConditional(
      rng, [&](int p) { return p != b1 && sameRegion(p) && consistentWith(p, b1); }, candidates);
  if (base[1] < 0) return false;

  // pi(p | b1, b2): also phi(p, b2) and a wide angle at b1 between b1b2 and b1p.
  const int b2 = base[1];
  const Eigen::Vector3f e12 = (pts[b2] - pts[b1]).normalized();
  auto wideAngle = [&](int p) {
    const Eigen::Vector3f e1p = pts[p] - pts[b1];
    const float len = e1p.norm();
    return len > 0 && std::abs(e12.dot(e1p) / len) <= cos_wide_;
  };
  base[2] = drawConditional(
      rng,
      [&](int p) {
        return p != b2 && wideAngle(p) && sameRegion(p) && consistentWith(p, b1) &&
               consistentWith(p, b2);
      },
      candidates);
  if (base[2] < 0) return false;

  // pi(p | b1, b2, b3) = pi(p | b1, b2) phi(p, b3), zero off the plane through b1, b2, b3: the
  // wide-angle condition of the previous step carries over.
  const int b3 = base[2];
  const Eigen::Vector3f plane_normal = e12.cross(pts[b3] - pts[b1]).normalized();
  base[3] = drawConditional(
      rng,
      [&](int p) {
        return p != b2 && p != b3 &&
               std::abs(plane_normal.dot(pts[p] - pts[b1])) <= params_.coplanarity &&
               wideAngle(p) && sameRegion(p) && consistentWith(p, b1) && consistentWith(p, b2) &&
               consistentWith(p, b3);
      },
      candidates);
  return base[3] >= 0;
}

}  // namespace stocs
