#include "base_verification.h"

#include <algorithm>
#include <chrono>
#include <numeric>
#include <optional>

#include "elapsed.h"
#include "stocs/geometry/rigid_fit.h"

namespace stocs {
namespace {

using Clock = std::chrono::steady_clock;

/// The rounds in which the hypotheses of a base are scored on their heads: after each share of the
/// head, the best `width` x finished_per_base of them go on (after the last, to be finished). An
/// early round (a quarter of the head, a few scene lookups) only has to keep the best few in, and
/// on planar bases the rounds drop most of the hypotheses long before the head's end.
struct HeadRound {
  float share;
  size_t width;
};
constexpr HeadRound kHeadRounds[] = {{0.25f, 8}, {0.5f, 4}, {1.0f, 1}};

}  // namespace

void BaseVerifier::run(int b, BaseOutcome& out) {
  out.tried = true;
  Rng rng(streamSeed(s_.params.seed, static_cast<uint64_t>(b)));
  // A base with nothing to verify is drawn again from its own stream (base_draw_budget).
  scored_.clear();
  const BaseWeighting weighting =
      b < s_.params.focused_bases ? BaseWeighting::kFocused : BaseWeighting::kSegment;
  const int draws = std::max(1, s_.params.base_draw_budget / s_.params.bases);
  for (int draw_index = 0; draw_index < draws && scored_.empty(); ++draw_index) {
    if (!draw(rng, weighting, out)) return;
  }
  verify(out);
}

bool BaseVerifier::draw(Rng& rng, BaseWeighting weighting, BaseOutcome& out) {
  ++out.draws;
  Clock::time_point t = Clock::now();
  const std::optional<Base> base = s_.sampler.sample(rng, sampling_, weighting);
  out.stages.sampling += secondsSince(t);
  if (!base) return false;
  out.sampled = true;
  out.region = s_.segment.region.empty() ? -1 : s_.segment.region[(*base)[0]];

  std::array<Eigen::Vector3f, 4> points, normals;
  for (int k = 0; k < 4; ++k) {
    points[k] = s_.segment.points[(*base)[k]];
    normals[k] = s_.segment.normals[(*base)[k]];
  }
  t = Clock::now();
  s_.matcher.find(points, normals, rng, sets_, matching_);
  out.stages.matching += secondsSince(t);
  out.sets += static_cast<int>(sets_.size());

  t = Clock::now();
  keepHypotheses(points, normals, out);
  out.stages.verification += secondsSince(t);
  return true;
}

void BaseVerifier::keepHypotheses(const std::array<Eigen::Vector3f, 4>& points,
                                  const std::array<Eigen::Vector3f, 4>& normals, BaseOutcome& out) {
  const ObjectModel& model = s_.model;
  for (const CongruentSet& set : sets_) {
    const std::array<Eigen::Vector3f, 4> mp = {model.points[set[0]], model.points[set[1]],
                                               model.points[set[2]], model.points[set[3]]};
    const std::optional<Eigen::Isometry3f> pose = fitRigid(mp, points, s_.params.max_fit_rms);
    if (!pose) continue;
    if (!normalsAgree(*pose, set, normals)) {
      ++out.normal_mismatches;
      continue;
    }
    const PlacedPose placed{*pose, *pose * s_.proximity.centre()};
    if (isNearDuplicate(placed)) {
      ++out.duplicates;
      continue;
    }
    scored_.push_back(placed);
  }
}

void BaseVerifier::verify(BaseOutcome& out) {
  const Clock::time_point t = Clock::now();
  out.hypotheses = static_cast<long>(scored_.size());
  rankHeads(out);
  out.finished = static_cast<long>(order_.size());
  // The best heads are finished, best first: the base's best is found early, and the coarse checks
  // and the exact bound drop the others soon after their head.
  for (uint32_t h : order_) {
    const float kth = thread_top_.size() < s_.keep ? -std::numeric_limits<float>::infinity()
                                                   : thread_top_.front();
    const float score = s_.scorer.finishScore(s_.model, scored_[h].pose, out.region, heads_[h],
                                              std::max(kth, out.score));
    if (score > out.score) {  // strict: of equal scores, the first in this order keeps it
      out.score = score;
      out.pose = scored_[h].pose;
    }
  }
  out.stages.verification += secondsSince(t);
  if (out.score > -std::numeric_limits<float>::infinity()) {
    thread_top_.insert(std::upper_bound(thread_top_.begin(), thread_top_.end(), out.score),
                       out.score);
    if (thread_top_.size() > s_.keep) thread_top_.erase(thread_top_.begin());
  }
}

void BaseVerifier::rankHeads(const BaseOutcome& out) {
  // Heads in rounds (kHeadRounds): every hypothesis on the first share of the head, the most
  // promising of them on the next, and so on to the whole head. Every (partial) head covers the
  // same model points, so their objectives compare directly.
  heads_.assign(scored_.size(), PartialScore{});
  order_.resize(scored_.size());
  std::iota(order_.begin(), order_.end(), 0u);
  const auto finished = static_cast<size_t>(s_.params.finished_per_base);
  for (const HeadRound& round : kHeadRounds) {
    for (uint32_t h : order_) {
      s_.scorer.extendHead(s_.model, scored_[h].pose, out.region, heads_[h], round.share);
    }
    const size_t n = std::min(round.width * finished, order_.size());
    std::partial_sort(order_.begin(), order_.begin() + static_cast<std::ptrdiff_t>(n), order_.end(),
                      [&](uint32_t a, uint32_t b) {
                        return heads_[a].total > heads_[b].total ||
                               (heads_[a].total == heads_[b].total && a < b);
                      });
    order_.resize(n);
  }
}

bool BaseVerifier::isNearDuplicate(const PlacedPose& pose) const {
  const float d = s_.params.duplicate_distance;
  return std::any_of(scored_.begin(), scored_.end(), [&](const PlacedPose& s) {
    // The centre's move is part of the bound and rules out most pairs with three subtractions.
    return (s.centre - pose.centre).squaredNorm() < d * d &&
           s_.proximity.within(pose.pose, s.pose, d);
  });
}

bool BaseVerifier::normalsAgree(const Eigen::Isometry3f& pose, const CongruentSet& set,
                                const std::array<Eigen::Vector3f, 4>& base_normals) const {
  int agree = 0;
  for (int k = 0; k < 4; ++k) {
    agree += s_.scorer.normalsAgree(pose.linear() * s_.model.normals[set[k]], base_normals[k]);
  }
  return agree >= s_.params.min_normal_agreement;
}

}  // namespace stocs
