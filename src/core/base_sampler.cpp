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

bool BaseSampler::tryComplete(Rng& rng, Base& base,
                              std::vector<std::pair<int, float>>& candidates) const {
  const auto& pts = segment_.points;
  const auto& nrm = segment_.normals;
  const int b1 = base[0];
  // pi(p | b1) ~ pi_k(p) phi(p, b1). Only candidates with a positive weight are carried forward, so
  // each later step costs the number of survivors, not the segment size.
  candidates.clear();
  double total = 0;
  const bool regions = !segment_.region.empty();
  for (int p = 0; p < static_cast<int>(pts.size()); ++p) {
    if (p == b1 || (regions && segment_.region[p] != segment_.region[b1])) continue;
    if (!map_.consistent(pts[b1], nrm[b1], pts[p], nrm[p])) continue;
    candidates.emplace_back(p, segment_.probability[p]);
    total += segment_.probability[p];
  }
  if (candidates.empty()) return false;
  base[1] = drawWeighted(rng, candidates, total);

  // pi(p | b1, b2): also phi(p, b2) and a wide angle at b1 between b1b2 and b1p.
  const int b2 = base[1];
  const Eigen::Vector3f e12 = (pts[b2] - pts[b1]).normalized();
  auto keep = [&](auto&& admissible) {
    total = 0;
    size_t w = 0;
    for (const auto& c : candidates) {
      if (!admissible(c.first)) continue;
      candidates[w++] = c;
      total += c.second;
    }
    candidates.resize(w);
    return w > 0;
  };
  const bool found3 = keep([&](int p) {
    if (p == b2) return false;
    const Eigen::Vector3f e1p = pts[p] - pts[b1];
    const float len = e1p.norm();
    if (!(len > 0) || std::abs(e12.dot(e1p) / len) > cos_wide_) return false;
    return map_.consistent(pts[b2], nrm[b2], pts[p], nrm[p]);
  });
  if (!found3) return false;
  base[2] = drawWeighted(rng, candidates, total);

  // pi(p | b1, b2, b3): also phi(p, b3) and within epsilon_2 of the plane through b1, b2, b3.
  const int b3 = base[2];
  const Eigen::Vector3f plane_normal = e12.cross(pts[b3] - pts[b1]).normalized();
  const bool found4 = keep([&](int p) {
    if (p == b3 || std::abs(plane_normal.dot(pts[p] - pts[b1])) > params_.coplanarity) return false;
    return map_.consistent(pts[b3], nrm[b3], pts[p], nrm[p]);
  });
  if (!found4) return false;
  base[3] = drawWeighted(rng, candidates, total);
  return true;
}

}  // namespace stocs
