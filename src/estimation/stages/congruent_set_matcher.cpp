#include "stocs/estimation/stages/congruent_set_matcher.h"

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

/// The split of the base into two pairs whose lines cross best: inside both segments if possible,
/// then at the widest angle.
LinePair bestSplit(const std::array<Eigen::Vector3f, 4>& points) {
  const LinePair splits[3] = {closestPoints(points, 0, 1, 2, 3), closestPoints(points, 0, 2, 1, 3),
                              closestPoints(points, 0, 3, 1, 2)};
  const LinePair* best = &splits[0];
  for (const LinePair& s : splits) {
    if (std::make_pair(s.inside, s.sin_angle) > std::make_pair(best->inside, best->sin_angle))
      best = &s;
  }
  return *best;
}

/// The model pairs whose PPF matches base pair (a, b) into workspace.first and those matching
/// (c, d) into workspace.second; false when either has none.
bool matchPairs(const PpfHashMap& ppf_map, const LinePair& split,
                const std::array<Eigen::Vector3f, 4>& points,
                const std::array<Eigen::Vector3f, 4>& normals,
                CongruentSetMatcher::Workspace& workspace) {
  std::vector<ModelPair>& first = workspace.first;
  std::vector<ModelPair>& second = workspace.second;
  first.clear();
  second.clear();
  const int a = split.a, b = split.b, c = split.c, d = split.d;
  ppf_map.forEachMatch(points[a], normals[a], points[b], normals[b], [&](uint16_t i, uint16_t j) {
    first.push_back({i, j});
  });
  if (first.empty()) return false;
  ppf_map.forEachMatch(points[c], normals[c], points[d], normals[d], [&](uint16_t k, uint16_t l) {
    second.push_back({k, l});
  });
  return !second.empty();
}

/// The tests of model pairs against a base split into pairs (a, b) and (c, d).
class CongruenceTest {
 public:
  CongruenceTest(const std::array<Eigen::Vector3f, 4>& base, const LinePair& split,
                 const std::vector<Eigen::Vector3f>& model_points, float tolerance)
      : split_(split),
        mp_(model_points),
        tolerance_(tolerance),
        ab_(bound(base[split.a], base[split.b], tolerance)),
        cd_(bound(base[split.c], base[split.d], tolerance)),
        ac_(bound(base[split.a], base[split.c], tolerance)),
        ad_(bound(base[split.a], base[split.d], tolerance)),
        bc_(bound(base[split.b], base[split.c], tolerance)),
        bd_(bound(base[split.b], base[split.d], tolerance)) {}

  /// True when first pair f is as long as base pair (a, b), within the tolerance.
  bool firstFits(ModelPair f) const { return agrees(ab_, f.first, f.second); }

  /// True when second pair s completes first pair f to a set congruent to the base: four distinct
  /// model points, and the five distances not tested by firstFits within the tolerance.
  bool completes(ModelPair f, const ModelPair& s) const {
    if (s.first == f.first || s.first == f.second || s.second == f.first || s.second == f.second) {
      return false;
    }
    return agrees(cd_, s.first, s.second) && agrees(ac_, f.first, s.first) &&
           agrees(ad_, f.first, s.second) && agrees(bc_, f.second, s.first) &&
           agrees(bd_, f.second, s.second);
  }

  /// The set of first pair f and second pair s, in base order.
  CongruentSet set(ModelPair f, ModelPair s) const {
    CongruentSet set;
    set[split_.a] = f.first;
    set[split_.b] = f.second;
    set[split_.c] = s.first;
    set[split_.d] = s.second;
    return set;
  }

  /// Where first pair f meets the other line: at ratio t along it.
  Eigen::Vector3f firstMeeting(ModelPair f) const {
    return mp_[f.first] + split_.t * (mp_[f.second] - mp_[f.first]);
  }
  /// Where second pair s meets the other line: at ratio u along it.
  Eigen::Vector3f secondMeeting(ModelPair s) const {
    return mp_[s.first] + split_.u * (mp_[s.second] - mp_[s.first]);
  }
  /// How far the meeting points of a congruent set's pairs may lie apart: the base's own line gap
  /// and the tolerance.
  float meetingRadius() const { return split_.gap + tolerance_; }

 private:
  /// A model distance d matches base distance b within the tolerance, tested on squared lengths
  /// (no square root per candidate pair): |d - b| <= tol iff (b - tol)^2 <= d^2 <= (b + tol)^2 for
  /// b - tol >= 0, and d^2 <= (b + tol)^2 otherwise.
  struct Bound {
    float lo2, hi2;
  };
  /// The bounds of the distance between base points p and q.
  static Bound bound(const Eigen::Vector3f& p, const Eigen::Vector3f& q, float tolerance) {
    const float d = (p - q).norm();
    return {d > tolerance ? (d - tolerance) * (d - tolerance) : 0.0f,
            (d + tolerance) * (d + tolerance)};
  }
  /// True when model points i and j are as far apart as `bound` allows.
  bool agrees(const Bound& bound, uint16_t i, uint16_t j) const {
    const float d2 = (mp_[i] - mp_[j]).squaredNorm();
    return d2 >= bound.lo2 && d2 <= bound.hi2;
  }

  const LinePair split_;
  const std::vector<Eigen::Vector3f>& mp_;
  const float tolerance_;
  const Bound ab_, cd_, ac_, ad_, bc_, bd_;  // of the six base distances
};

/// The congruent sets of the workspace's first and second pairs, up to `cap`, into `out`.
void collectSets(const CongruenceTest& test, size_t cap, Rng& rng,
                 CongruentSetMatcher::Workspace& workspace, std::vector<CongruentSet>& out) {
  const std::vector<ModelPair>& second = workspace.second;
  workspace.meeting.clear();
  for (const ModelPair& s : second) workspace.meeting.push_back(test.secondMeeting(s));
  const float radius = test.meetingRadius();
  workspace.grid.assign(workspace.meeting, radius);
  // First pairs are visited in a seeded random order (a Fisher-Yates shuffle drawn lazily, from
  // the back, as far as the visit goes) and the search stops at the cap: the sets kept are a random
  // sample without enumerating, or even shuffling, every pair of a very ambiguous (e.g. planar)
  // base, which typically fills the cap from a few dozen of its thousands of first pairs.
  std::vector<ModelPair>& first = workspace.first;
  for (size_t k = first.size(); k > 0 && out.size() < cap; --k) {
    std::swap(first[k - 1], first[uniformIndex(rng, static_cast<uint32_t>(k))]);
    const ModelPair f = first[k - 1];
    if (!test.firstFits(f)) continue;
    workspace.grid.forEachWithin(test.firstMeeting(f), radius, [&](int s_index, float) {
      const ModelPair& s = second[s_index];
      if (out.size() >= cap) return;
      if (test.completes(f, s)) out.push_back(test.set(f, s));
    });
  }
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
  const LinePair split = bestSplit(points);
  if (split.sin_angle < min_line_sin_) return 0;
  if (!matchPairs(model_.ppf_map, split, points, normals, workspace)) return 0;
  const CongruenceTest test(points, split, model_.model.points, params_.tolerance);
  collectSets(test, static_cast<size_t>(params_.max_sets), rng, workspace, out);
  // Each (first, second) combination is visited at most once, so sets are distinct by construction.
  return out.size();
}

}  // namespace stocs
