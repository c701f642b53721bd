#include "stocs/estimation/stages/base_sampler.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "stocs/util/error.h"

namespace stocs {
namespace {

/// Sum of the weights before position k of the prefix sums `cumulative`.
double sumBefore(const std::vector<double>& cumulative, size_t k) {
  return k > 0 ? cumulative[k - 1] : 0.0;
}

/// A position i in [begin, end) drawn with probability proportional to its weight
/// cumulative[i] - sumBefore(cumulative, i).
size_t drawByPrefixSums(Rng& rng, const std::vector<double>& cumulative, size_t begin, size_t end) {
  const double before = sumBefore(cumulative, begin);
  const double target = before + uniform01(rng) * (cumulative[end - 1] - before);
  const auto first = cumulative.begin() + static_cast<std::ptrdiff_t>(begin),
             last = cumulative.begin() + static_cast<std::ptrdiff_t>(end);
  // The clamp: rounding at the very end of the range.
  return static_cast<size_t>(std::min(std::upper_bound(first, last, target), last - 1) -
                             cumulative.begin());
}

size_t drawByPrefixSums(Rng& rng, const std::vector<double>& cumulative) {
  return drawByPrefixSums(rng, cumulative, 0, cumulative.size());
}

/// x^n for n >= 1 by squaring: std::pow costs several times more, once per point per estimate.
double integerPower(double x, int n) {
  double result = 1;
  for (; n > 0; n >>= 1, x *= x) {
    if (n & 1) result *= x;
  }
  return result;
}

}  // namespace

const ParamSet<BaseSamplerParams>& BaseSamplerParams::schema() {
  static const ParamSet<BaseSamplerParams> schema =
      ParamSet<BaseSamplerParams>()
          .add(&BaseSamplerParams::wide_angle_deg, "wide_angle_deg", "deg",
               ParamRange::fromBelow(0, 90),
               "epsilon_1: smallest angle at b1 between b1b2 and b1b3 (and to 180)")
          .flag("--wide-angle")
          .add(&BaseSamplerParams::coplanarity, "coplanarity", "m", ParamRange::aboveUpTo(0, 0.1),
               "epsilon_2: largest distance of b4 from the plane of b1, b2, b3")
          .flag("--coplanarity")
          .add(&BaseSamplerParams::max_attempts, "max_attempts", "", ParamRange::closed(1, 10000),
               "fresh draws of b1 before a base counts as failed")
          .add(&BaseSamplerParams::focus_exponent, "focus_exponent", "",
               ParamRange::closed(1, kMaxFocusExponent),
               "focused bases draw their points by pi_k to this power")
          .flag("--focus-exponent");
  return schema;
}

void BaseSamplerParams::validate() const {
  schema().validate(*this);
}

BaseSampler::BaseSampler(const SoftSegment& segment, const PpfHashMap& map,
                         const BaseSamplerParams& params)
    : segment_(segment),
      map_(map),
      params_(params),
      // An empty map (no pairs) has no length: any positive cell size serves.
      reach_(std::max(map.maxDistance(), 1e-3f)),
      cos_wide_(std::cos(params.wide_angle_deg * static_cast<float>(M_PI) / 180.0f)) {
  params_.validate();
  grid_.assign(segment.points, reach_);
  segment_weights_ = weigh(1);
  if (params_.focus_exponent > 1) focused_weights_ = weigh(params_.focus_exponent);
}

BaseSampler::Weights BaseSampler::weigh(int exponent) const {
  Weights w;
  w.cumulative.reserve(segment_.size());
  double acc = 0;
  for (size_t i = 0; i < segment_.size(); ++i) {
    const bool on_boundary = !segment_.region.empty() && segment_.region[i] < 0;
    w.cumulative.push_back(acc +=
                           on_boundary ? 0.0 : integerPower(segment_.probability[i], exponent));
  }
  w.grid_cumulative.reserve(segment_.size());
  acc = 0;
  for (uint32_t k = 0; k < grid_.size(); ++k) {
    w.grid_cumulative.push_back(acc += w.of(static_cast<int>(grid_.originalIndex(k))));
  }
  return w;
}

double BaseSampler::Weights::of(int i) const {
  return cumulative[i] - sumBefore(cumulative, static_cast<size_t>(i));
}

std::optional<Base> BaseSampler::sample(Rng& rng, BaseSamplingScratch& scratch,
                                        BaseWeighting weighting) const {
  const Weights& w = weighting == BaseWeighting::kFocused && params_.focus_exponent > 1
                         ? focused_weights_
                         : segment_weights_;
  if (segment_.size() < 4 || !(w.cumulative.back() > 0)) return std::nullopt;
  for (int attempt = 0; attempt < params_.max_attempts; ++attempt) {
    Base base{static_cast<int>(drawByPrefixSums(rng, w.cumulative)), -1, -1, -1};
    if (tryComplete(w, rng, base, scratch)) return base;
  }
  return std::nullopt;
}

bool BaseSampler::gatherNeighbourhood(const Weights& w, int b1,
                                      BaseSamplingScratch& scratch) const {
  scratch.runs.clear();
  scratch.run_cumulative.clear();
  double total = 0;
  grid_.forEachRun(segment_.points[b1], reach_, [&](uint32_t begin, uint32_t end) {
    scratch.runs.push_back({begin, end});
    scratch.run_cumulative.push_back(total += w.grid_cumulative[end - 1] -
                                              sumBefore(w.grid_cumulative, begin));
  });
  return total > 0;
}

int BaseSampler::drawNear(const Weights& w, Rng& rng, const BaseSamplingScratch& scratch) const {
  const auto [begin, end] = scratch.runs[drawByPrefixSums(rng, scratch.run_cumulative)];
  const size_t k = drawByPrefixSums(rng, w.grid_cumulative, begin, end);
  return static_cast<int>(grid_.originalIndex(static_cast<uint32_t>(k)));
}

template <class Geometric, class OnModel>
int BaseSampler::drawConditional(const Weights& w, Rng& rng, Geometric&& geometric,
                                 OnModel&& on_model, BaseSamplingScratch& scratch) const {
  // Rejection sampling in up to three rounds. Proposals from a distribution proportional to the
  // weights on a superset of the admissible points, accepted when admissible, are distributed
  // exactly as the weights restricted to the admissible points, and so is the result whichever
  // round gives it.
  // Round 1 proposes from the cells around b1. When admissible points are rare there (b4 must lie
  // in a plane), round 2 proposes among the points of those cells that pass the geometric tests,
  // found by one scan without PPF checks; round 3 checks all of those.
  constexpr int kProposals = 128;
  for (int t = 0; t < kProposals; ++t) {
    const int p = drawNear(w, rng, scratch);
    // Weight > 0: rounding at the end of a run may land on a point without weight.
    if (w.of(p) > 0 && geometric(p) && on_model(p)) return p;
  }
  std::vector<int>& points = scratch.points;
  std::vector<double>& cumulative = scratch.cumulative;
  points.clear();
  cumulative.clear();
  double total = 0;
  for (const auto& [begin, end] : scratch.runs) {
    for (uint32_t k = begin; k < end; ++k) {
      const int p = static_cast<int>(grid_.originalIndex(k));
      const double weight = w.grid_cumulative[k] - sumBefore(w.grid_cumulative, k);
      if (weight > 0 && geometric(p)) {
        points.push_back(p);
        cumulative.push_back(total += weight);
      }
    }
  }
  if (points.empty()) return -1;
  for (int t = 0; t < kProposals; ++t) {
    const int p = points[drawByPrefixSums(rng, cumulative)];
    if (on_model(p)) return p;
  }
  size_t kept = 0;
  double previous = 0;
  total = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const double weight = cumulative[i] - previous;
    previous = cumulative[i];
    if (on_model(points[i])) {
      points[kept] = points[i];
      cumulative[kept++] = total += weight;
    }
  }
  if (kept == 0) return -1;
  points.resize(kept);
  cumulative.resize(kept);
  return points[drawByPrefixSums(rng, cumulative)];
}

bool BaseSampler::tryComplete(const Weights& w, Rng& rng, Base& base,
                              BaseSamplingScratch& scratch) const {
  const auto& pts = segment_.points;
  const auto& nrm = segment_.normals;
  const bool regions = !segment_.region.empty();
  auto sameRegion = [&](int p) {
    return !regions || segment_.region[p] == segment_.region[base[0]];
  };
  auto consistentWith = [&](int p, int b) {
    return map_.consistent(pts[b], nrm[b], pts[p], nrm[p]);
  };

  // pi(p | b1) ~ w(p) phi(p, b1), with w the draw's weights: pi_k, or its power in a focused draw.
  const int b1 = base[0];
  if (!gatherNeighbourhood(w, b1, scratch)) return false;
  base[1] = drawConditional(
      w, rng, [&](int p) { return p != b1 && sameRegion(p); },
      [&](int p) { return consistentWith(p, b1); }, scratch);
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
      w, rng, [&](int p) { return p != b2 && wideAngle(p) && sameRegion(p); },
      [&](int p) { return consistentWith(p, b1) && consistentWith(p, b2); }, scratch);
  if (base[2] < 0) return false;

  // pi(p | b1, b2, b3) = pi(p | b1, b2) phi(p, b3), zero off the plane through b1, b2, b3: the
  // wide-angle condition of the previous step carries over.
  const int b3 = base[2];
  const Eigen::Vector3f plane_normal = e12.cross(pts[b3] - pts[b1]).normalized();
  base[3] = drawConditional(
      w, rng,
      [&](int p) {
        return p != b2 && p != b3 &&
               std::abs(plane_normal.dot(pts[p] - pts[b1])) <= params_.coplanarity &&
               wideAngle(p) && sameRegion(p);
      },
      [&](int p) {
        return consistentWith(p, b1) && consistentWith(p, b2) && consistentWith(p, b3);
      },
      scratch);
  return base[3] >= 0;
}

}  // namespace stocs
