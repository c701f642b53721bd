#include "stocs/estimation/congruent_set_matcher.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "stocs/util/error.h"

namespace stocs {
namespace {

struct LinePair {
  int a, b, c, d;  // base indices: line ab and line cd
  float t, u;      // closest points: a + t (b - a) and c + u (d - c)
  float gap;       // distance between those closest points
  float sin_angle;
  bool inside;  // both closest points within their segments
};

LinePair closestPoints(const std::array<Eigen::Vector3f, 4>& p, int a, int b, int c, int d) {
  const Eigen::Vector3f r = p[b] - p[a], s = p[d] - p[c], w = p[a] - p[c];
  const float rr = r.dot(r), ss = s.dot(s), rs = r.dot(s), rw = r.dot(w), sw = s.dot(w);
  const float denom = rr * ss - rs * rs;  // = |r|^2 |s|^2 sin^2
  LinePair lp{a, b, c, d, 0, 0, 0, 0, false};
  if (!(denom > 1e-12f * rr * ss)) return lp;  // parallel lines
  lp.t = (rs * sw - ss * rw) / denom;
  lp.u = (rr * sw - rs * rw) / denom;
  lp.gap = ((p[a] + lp.t * r) - (p[c] + lp.u * s)).norm();
  lp.sin_angle = std::sqrt(denom / (rr * ss));
  lp.inside = lp.t >= 0 && lp.t <= 1 && lp.u >= 0 && lp.u <= 1;
  return lp;
}

}  // namespace

const ParamSet<CongruentSetParams>& CongruentSetParams::schema() {
  static const ParamSet<CongruentSetParams> schema =
      ParamSet<CongruentSetParams>()
          .add(&CongruentSetParams::tolerance, "tolerance", "m", ParamRange::aboveUpTo(0, 0.1),
               "distance tolerance of congruent sets (sensor noise plus model sampling)")
          .flag("--congruence-tolerance")
          .add(&CongruentSetParams::max_sets, "max_sets", "", ParamRange::closed(1, 100000),
               "congruent sets verified per base at most")
          .flag("--max-sets")
          .add(&CongruentSetParams::min_line_angle_deg, "min_line_angle_deg", "deg",
               ParamRange::fromBelow(0, 90),
               "bases whose best pair split crosses flatter than this are skipped");
  return schema;
}

void CongruentSetParams::validate() const {
  schema().validate(*this);
}

CongruentSetMatcher::CongruentSetMatcher(const PreparedModel& model,
                                         const CongruentSetParams& params)
    : model_(model),
      params_(params),
      min_line_sin_(std::sin(params.min_line_angle_deg * static_cast<float>(M_PI) / 180.0f)) {
  params_.validate();
}

size_t CongruentSetMatcher::find(const std::array<Eigen::Vector3f, 4>& points,
                                 const std::array<Eigen::Vector3f, 4>& normals, Rng& rng,
                                 std::vector<CongruentSet>& out, Workspace& workspace) const {
  out.clear();
  // The split of the base into two pairs whose lines cross best: inside both segments if possible,
  // then at the widest angle.
  const LinePair splits[3] = {closestPoints(points, 0, 1, 2, 3), closestPoints(points, 0, 2, 1, 3),
                              closestPoints(points, 0, 3, 1, 2)};
  const LinePair* best = &splits[0];
  for (const LinePair& s : splits) {
    if (std::make_pair(s.inside, s.sin_angle) > std::make_pair(best->inside, best->sin_angle))
      best = &s;
  }
  if (best->sin_angle < min_line_sin_) return 0;
  const LinePair& lp = *best;

  const auto& mp = model_.model.points;
  std::vector<ModelPair>& first = workspace.first;
  std::vector<ModelPair>& second = workspace.second;
  first.clear();
  second.clear();
  model_.ppf_map.forEachMatch(points[lp.a], normals[lp.a], points[lp.b], normals[lp.b],
                              [&](uint16_t i, uint16_t j) {
                                first.push_back({i, j});
                              });
  if (first.empty()) return 0;
  model_.ppf_map.forEachMatch(points[lp.c], normals[lp.c], points[lp.d], normals[lp.d],
                              [&](uint16_t k, uint16_t l) {
                                second.push_back({k, l});
                              });
  if (second.empty()) return 0;

  // Six base distances; a congruent set matches each within the tolerance, tested on squared
  // lengths (no square root per candidate pair): |d - b| <= tol iff (b - tol)^2 <= d^2 <= (b +
  // tol)^2 for b - tol >= 0, and d^2 <= (b + tol)^2 otherwise.
  const float tol = params_.tolerance;
  float lo2[4][4], hi2[4][4];
  for (int x = 0; x < 4; ++x) {
    for (int y = 0; y < 4; ++y) {
      const float d = (points[x] - points[y]).norm();
      lo2[x][y] = d > tol ? (d - tol) * (d - tol) : 0.0f;
      hi2[x][y] = (d + tol) * (d + tol);
    }
  }
  auto agrees = [&](int x, int y, uint16_t mx, uint16_t my) {
    const float d2 = (mp[mx] - mp[my]).squaredNorm();
    return d2 >= lo2[x][y] && d2 <= hi2[x][y];
  };

  workspace.meeting.clear();
  for (const ModelPair& p : second) {
    workspace.meeting.push_back(mp[p.first] + lp.u * (mp[p.second] - mp[p.first]));
  }
  const float radius = lp.gap + tol;
  workspace.grid.assign(workspace.meeting, radius);
  // First pairs are visited in a seeded random order (a Fisher-Yates shuffle drawn lazily, from
  // the back, as far as the visit goes) and the search stops at the cap: the sets kept are a random
  // sample without enumerating, or even shuffling, every pair of a very ambiguous (e.g. planar)
  // base, which typically fills the cap from a few dozen of its thousands of first pairs.
  const size_t cap = static_cast<size_t>(params_.max_sets);
  for (size_t k = first.size(); k > 0 && out.size() < cap; --k) {
    std::swap(first[k - 1], first[uniformIndex(rng, static_cast<uint32_t>(k))]);
    const ModelPair f = first[k - 1];
    if (!agrees(lp.a, lp.b, f.first, f.second)) continue;
    const Eigen::Vector3f meeting = mp[f.first] + lp.t * (mp[f.second] - mp[f.first]);
    workspace.grid.forEachWithin(meeting, radius, [&](int s_index, float) {
      const ModelPair& s = second[s_index];
      if (out.size() >= cap) return;
      if (s.first == f.first || s.first == f.second || s.second == f.first ||
          s.second == f.second) {
        return;
      }
      if (!agrees(lp.c, lp.d, s.first, s.second) || !agrees(lp.a, lp.c, f.first, s.first) ||
          !agrees(lp.a, lp.d, f.first, s.second) || !agrees(lp.b, lp.c, f.second, s.first) ||
          !agrees(lp.b, lp.d, f.second, s.second)) {
        return;
      }
      CongruentSet set;
      set[lp.a] = f.first;
      set[lp.b] = f.second;
      set[lp.c] = s.first;
      set[lp.d] = s.second;
      out.push_back(set);
    });
  }
  // Each (first, second) combination is visited at most once, so sets are distinct by construction.
  return out.size();
}

}  // namespace stocs
