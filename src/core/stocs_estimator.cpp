#include "stocs/stocs_estimator.h"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <utility>
#include <vector>

#include "stocs/base_consensus.h"
#include "stocs/error.h"
#include "stocs/instance_separation.h"
#include "stocs/rigid_fit.h"

namespace stocs {
namespace {

using Clock = std::chrono::steady_clock;

/// The rounds in which the hypotheses of a base are scored on their heads: after each share of the
/// head, the best `width` x finished_per_base of them go on (after the last, to be finished). An
/// early round (a quarter of the head is often some 10 scene lookups) only has to keep the best
/// few in, and on planar bases the rounds drop most of the hypotheses long before the head's end.
struct HeadRound {
  float share;
  size_t width;
};
constexpr HeadRound kHeadRounds[] = {{0.25f, 8}, {0.5f, 4}, {1.0f, 1}};

/// The consensus stop's free-space limit: the best base's pose may put at most this share of its
/// camera-facing surface where the sensor sees through. Of the wrong poses agreement alone stopped
/// on, slid boxes and turned-over blocks had 19-51% there (refined); objects whose best raw pose
/// exceeds the limit just run every base.
/// The unrefined pose is judged: judged after ICP, wrong poses passed more often (BENCHMARKS.md,
/// "Consensus stop").
constexpr float kConsensusFreeSpace = 0.05f;

double secondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

/// What one base produced: its best hypothesis and counters.
struct BaseOutcome {
  bool tried = false, sampled = false;
  int draws = 0, sets = 0;
  long hypotheses = 0, duplicates = 0, normal_mismatches = 0, finished = 0;
  float score = -std::numeric_limits<float>::infinity();
  int region = -1;  // instance region of the base, -1 without regions
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  StageSeconds stages;
};

/// Hands out the bases to the threads in index order and runs the consensus stop between blocks
/// without a barrier: whoever completes the last outstanding base of a block checks it (blocks in
/// order), while the other threads go on with the next bases. Once a block reaches consensus, no
/// base after it starts, and those already started are dropped (dropSpeculative), so the result
/// is that of the bases up to that block for every thread count. A thread takes bases in
/// increasing order, so its pruning bound (the best scores it has seen) only ever holds bases of
/// lower index than the one it verifies: a dropped base never changes a kept one.
class BaseDispenser {
 public:
  BaseDispenser(int bases, BaseConsensus* consensus, std::vector<BaseOutcome>& outcomes)
      : end_(bases), consensus_(consensus), outcomes_(outcomes) {
    if (consensus_) finished_.assign(static_cast<size_t>(bases), 0);
  }

  /// The next base to run, or -1 when none is left.
  int next() {
    const int b = next_.fetch_add(1, std::memory_order_relaxed);
    return b < end_.load(std::memory_order_acquire) ? b : -1;
  }

  /// Base `b` has run (its outcome is written): check the blocks it completes.
  void finished(int b) {
    if (!consensus_) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    finished_[static_cast<size_t>(b)] = 1;
    const int end = end_.load(std::memory_order_relaxed);
    while (complete_ < end && finished_[static_cast<size_t>(complete_)]) {
      const BaseOutcome& out = outcomes_[static_cast<size_t>(complete_)];
      consensus_->add(complete_, out.score, out.pose);
      ++complete_;
      if (complete_ % StocsParams::kConsensusBlock == 0 && complete_ < end &&
          consensus_->reached()) {
        end_.store(complete_, std::memory_order_release);
        return;
      }
    }
  }

  /// After the threads are done: clears the outcomes of bases started after the consensus.
  void dropSpeculative() {
    for (size_t b = static_cast<size_t>(end_.load()); b < outcomes_.size(); ++b) outcomes_[b] = {};
  }

 private:
  std::atomic<int> next_{0};
  std::atomic<int> end_;  // bases from here on do not count
  BaseConsensus* consensus_;
  std::vector<BaseOutcome>& outcomes_;
  std::mutex mutex_;
  std::vector<char> finished_;  // per base, under mutex_
  int complete_ = 0;            // bases before it have all finished, under mutex_
};

/// A pose with its objective, before or after refinement.
struct Hypothesis {
  Eigen::Isometry3f pose;
  float score;
  int region;
  int base;               // the base it is the best of
  bool refined = false;   // ICP moved the pose and did not lower the objective
  bool polished = false;  // refinement was tried
};

bool higherScore(const Hypothesis& a, const Hypothesis& b) {
  return a.score > b.score;
}

/// `h` after point-to-plane refinement to `refined`: the refined pose is kept when it does not
/// lower the objective by more than 10% (a diverged refinement keeps the unrefined pose); then,
/// with a free-space check, the score is discounted by the share of the pose's visible surface in
/// free space.
Hypothesis judged(const Hypothesis& h, const Eigen::Isometry3f* refined, const ObjectModel& model,
                  const LcpScorer& scorer, const FreeSpaceCheck* free_space) {
  Hypothesis out = h;
  out.polished = true;
  if (refined) {
    const float score = scorer.score(model, *refined, h.region);
    if (score >= 0.9f * h.score) {
      out.pose = *refined;
      out.score = score;
      out.refined = !refined->isApprox(h.pose);
    }
  }
  if (free_space) out.score *= 1.0f - free_space->violation(model, out.pose);
  return out;
}

/// A candidate's refinement under way: its ICP run, and the candidate judged at the run's pose.
struct Refinement {
  Hypothesis start;  // the unrefined candidate
  IcpRun run;
  std::optional<Hypothesis> judged;  // at the run's pose, once judged there

  explicit Refinement(const Hypothesis& h) : start(h), run(h.pose) {}
};

/// The steps every candidate takes before the finalists are chosen (IcpParams::
/// screening_iterations), or all of them when there is no screening: screening is off, or no more
/// than IcpParams::finalists candidates would take part.
int firstSteps(const IcpParams& icp, size_t candidates) {
  const bool screening = icp.screening_iterations > 0 &&
                         icp.screening_iterations < icp.iterations &&
                         candidates > static_cast<size_t>(icp.finalists);
  return screening ? icp.screening_iterations : icp.iterations;
}

/// Runs `r` on to `steps` steps in all (unless it finished) and judges it there.
void refineTo(Refinement& r, int steps, const ObjectModel& model, const IcpRefiner& icp,
              const LcpScorer& scorer, const FreeSpaceCheck* free_space) {
  if (r.judged && (r.run.finished || r.run.iterations >= steps)) return;
  icp.iterate(model, r.run, steps, r.start.region, &scorer);
  r.judged = judged(r.start, &r.run.pose, model, scorer, free_space);
}

/// `h` refined to the end (or only judged without ICP); adds the ICP steps taken to `steps`.
Hypothesis refine(const Hypothesis& h, const ObjectModel& model, const IcpRefiner* icp,
                  const LcpScorer& scorer, const FreeSpaceCheck* free_space, long& steps) {
  if (!icp) return judged(h, nullptr, model, scorer, free_space);
  Refinement r(h);
  refineTo(r, icp->params().iterations, model, *icp, scorer, free_space);
  steps += r.run.iterations;
  return *r.judged;
}

/// The `first` best of `ranked` refined, in parallel: each refinement is independent and reads only
/// shared const state. With `screen`, every candidate first takes firstSteps() steps, and only the
/// IcpParams::finalists best of them by the judged objective take the others: a candidate's first
/// steps settle whether it is in the running, and most of the ICP time went into the later steps
/// of candidates that then lost. When several instances are wanted every candidate may be one, and
/// all are refined to the end. `early`, per base, holds refinements that the base loop began
/// (their first steps taken); the others begin here. Adds the ICP steps taken to `steps`.
std::vector<Hypothesis> refineCandidates(const std::vector<Hypothesis>& ranked, size_t first,
                                         bool screen, const ObjectModel& model,
                                         const IcpRefiner* icp, const LcpScorer& scorer,
                                         const FreeSpaceCheck* free_space,
                                         std::vector<std::optional<Refinement>>& early, int threads,
                                         long& steps) {
  std::vector<Hypothesis> pool(ranked.begin(), ranked.begin() + static_cast<std::ptrdiff_t>(first));
  if (!icp) {
    for (size_t k = 0; k < first; ++k)
      pool[k] = refine(ranked[k], model, icp, scorer, free_space, steps);
    return pool;
  }
  const IcpParams& params = icp->params();
  const int first_steps = screen ? firstSteps(params, first) : params.iterations;
  std::vector<Refinement> runs;
  runs.reserve(first);
  for (size_t k = 0; k < first; ++k) {
    std::optional<Refinement>& begun = early[static_cast<size_t>(ranked[k].base)];
    runs.push_back(begun ? std::move(*begun) : Refinement(ranked[k]));
  }
  auto runTo = [&](size_t k, int until) {
    refineTo(runs[k], until, model, *icp, scorer, free_space);
    pool[k] = *runs[k].judged;
  };
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
  for (size_t k = 0; k < first; ++k) runTo(k, first_steps);
  if (first_steps < params.iterations) {
    // The finalists: best judged objective first, ties to the better unrefined rank.
    std::vector<size_t> order(first);
    std::iota(order.begin(), order.end(), size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return pool[a].score > pool[b].score; });
    order.resize(static_cast<size_t>(params.finalists));
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
    for (size_t f = 0; f < order.size(); ++f) runTo(order[f], params.iterations);
  }
  for (const Refinement& r : runs) steps += r.run.iterations;
  return pool;
}

/// Up to `count` distinct poses from the bases' best hypotheses (`ranked`, best first). The
/// `refined_bases` best are refined first and compete by their refined objective (a 4-point
/// fit is a few mm off, and at delta_s such a right pose can score below a wrong one until it is
/// refined); then greedy non-maximum suppression: a hypothesis in the same place as one already
/// taken is skipped, and the others are refined when taken.
std::vector<InstancePose> selectInstances(const std::vector<Hypothesis>& ranked,
                                          size_t refined_bases, size_t count,
                                          const ObjectModel& model, const LcpScorer& scorer,
                                          const IcpRefiner* icp, const StocsParams& params,
                                          const FreeSpaceCheck* free_space,
                                          std::vector<std::optional<Refinement>>& early,
                                          int threads, long& steps) {
  const size_t first = std::min(refined_bases, ranked.size());
  std::vector<Hypothesis> pool = refineCandidates(ranked, first, count == 1, model, icp, scorer,
                                                  free_space, early, threads, steps);
  std::stable_sort(pool.begin(), pool.end(), higherScore);
  pool.insert(pool.end(), ranked.begin() + static_cast<std::ptrdiff_t>(first), ranked.end());

  std::optional<InstanceSeparation> separation;
  if (count > 1) separation.emplace(model, params.instance_separation * model.diameter);
  std::vector<Hypothesis> taken;
  auto isNew = [&](const Hypothesis& h) {
    return std::none_of(taken.begin(), taken.end(),
                        [&](const Hypothesis& t) { return separation->samePlace(h.pose, t.pose); });
  };
  for (Hypothesis h : pool) {
    if (taken.size() == count) break;
    if (!taken.empty() && !isNew(h)) continue;
    if (!h.polished) {
      h = refine(h, model, icp, scorer, free_space, steps);
      if (!taken.empty() && !isNew(h)) continue;  // refinement moved it onto a taken instance
    }
    taken.push_back(h);
  }
  std::stable_sort(taken.begin(), taken.end(), higherScore);
  std::vector<InstancePose> instances;
  for (const Hypothesis& h : taken) {
    instances.push_back({h.pose, scorer.detail(model, h.pose, h.region), h.refined, h.region});
  }
  return instances;
}

/// The scorer and the ICP refiner of a segment. Without instance regions each builds a
/// neighbourhood grid over the whole segment (milliseconds on large segments, before any base can
/// be verified), and they are independent, so they are built side by side; with regions the grids
/// are built on first use (RegionGrids).
struct SegmentIndexes {
  std::optional<LcpScorer> scorer;
  std::optional<IcpRefiner> icp;  // empty when ICP is off
};

/// Fills `out` in place: the scorer and the refiner hold once_flags and cannot move.
void buildIndexes(const SoftSegment& segment, const StocsParams& params, int threads,
                  SegmentIndexes& out) {
  std::exception_ptr error;  // an exception must not leave an OpenMP region
  auto guarded = [&](auto&& build) {
    try {
      build();
    } catch (...) {
#pragma omp critical(stocs_build_indexes)
      error = std::current_exception();
    }
  };
#pragma omp parallel sections num_threads(std::min(threads, 2))
  {
#pragma omp section
    guarded([&] { out.scorer.emplace(segment, params.lcp); });
#pragma omp section
    guarded([&] {
      if (params.icp.enabled) out.icp.emplace(segment, params.icp);
    });
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace

void StocsParams::validate() const {
  base.validate();
  congruent.validate();
  lcp.validate();
  icp.validate();
  free_space.validate();
  if (!(max_fit_rms > 0.0f && max_fit_rms <= 0.1f)) {
    throw InputError(fmt::format("rigid fit RMS limit {} m is outside (0, 0.1]", max_fit_rms));
  }
  if (!(duplicate_distance >= 0.0f && duplicate_distance <= 0.1f)) {
    throw InputError(
        fmt::format("duplicate hypothesis distance {} m is outside [0, 0.1]", duplicate_distance));
  }
  if (min_normal_agreement < 0 || min_normal_agreement > 4) {
    throw InputError(
        fmt::format("minimum normal agreement {} is outside [0, 4]", min_normal_agreement));
  }
  if (finished_per_base < 1 || finished_per_base > 100000) {
    throw InputError(
        fmt::format("hypotheses finished per base {} is outside [1, 100000]", finished_per_base));
  }
  if (bases < 1 || bases > 1000000)
    throw InputError(fmt::format("bases {} is outside [1, 1000000]", bases));
  if (base_draw_budget < 0 || base_draw_budget > 1000000) {
    throw InputError(fmt::format("base draw budget {} is outside [0, 1000000]", base_draw_budget));
  }
  if (focused_bases < 0 || focused_bases > 1000000) {
    throw InputError(fmt::format("focused bases {} is outside [0, 1000000]", focused_bases));
  }
  if (consensus_bases < 0 || consensus_bases > 1000) {
    throw InputError(fmt::format("consensus bases {} is outside [0, 1000]", consensus_bases));
  }
  if (!(time_budget >= 0) || time_budget > 3600) {
    throw InputError(fmt::format("time budget {} s is outside [0, 3600]", time_budget));
  }
  if (threads < 0 || threads > 256)
    throw InputError(fmt::format("threads {} is outside [0, 256]", threads));
  if (instances < 1 || instances > 100)
    throw InputError(fmt::format("instances {} is outside [1, 100]", instances));
  if (!(instance_separation > 0.0f && instance_separation <= 1.0f)) {
    throw InputError(
        fmt::format("instance separation {} (fraction of the diameter) is outside "
                    "(0, 1]",
                    instance_separation));
  }
}

StocsEstimator::StocsEstimator(const PreparedModel& model, const StocsParams& params)
    : model_(model),
      params_((params.validate(), params)),
      matcher_(model, params.congruent),
      proximity_(model.model) {}

bool StocsEstimator::isNearDuplicate(const PlacedPose& pose,
                                     const std::vector<PlacedPose>& scored) const {
  const float d = params_.duplicate_distance;
  return std::any_of(scored.begin(), scored.end(), [&](const PlacedPose& s) {
    // The centre's move is part of the bound and rules out most pairs with three subtractions.
    return (s.centre - pose.centre).squaredNorm() < d * d &&
           proximity_.within(pose.pose, s.pose, d);
  });
}

bool StocsEstimator::normalsAgree(const LcpScorer& scorer, const Eigen::Isometry3f& pose,
                                  const CongruentSet& set,
                                  const std::array<Eigen::Vector3f, 4>& base_normals) const {
  int agree = 0;
  for (int k = 0; k < 4; ++k) {
    agree += scorer.normalsAgree(pose.linear() * model_.model.normals[set[k]], base_normals[k]);
  }
  return agree >= params_.min_normal_agreement;
}

PoseEstimate StocsEstimator::estimate(const SoftSegment& segment,
                                      const FreeSpaceCheck* free_space) const {
  const Clock::time_point start = Clock::now();
  PoseEstimate result;
  if (segment.size() < 4) {
    result.seconds = secondsSince(start);
    return result;
  }
  const int threads = params_.threads > 0 ? params_.threads : omp_get_max_threads();
  const BaseSampler sampler(segment, model_.ppf_map, params_.base);
  SegmentIndexes indexes;
  buildIndexes(segment, params_, threads, indexes);
  const LcpScorer& scorer = *indexes.scorer;
  const ObjectModel& model = model_.model;
  const bool budgeted = params_.time_budget > 0;
  const Clock::time_point deadline =
      start + std::chrono::duration_cast<Clock::duration>(
                  std::chrono::duration<double>(params_.time_budget));

  std::vector<BaseOutcome> outcomes(params_.bases);
  // The K best bases go on to refinement, so a hypothesis matters when it can still beat its own
  // base's best and the K-th best base score seen so far. Several instances need every base's
  // best, as the next instance may come from any base.
  const size_t refined_bases =
      params_.icp.enabled ? static_cast<size_t>(params_.icp.candidates) : 1;
  // The consensus stop needs exact scores for the bases it compares: those of the `keep` best.
  // With a free-space check, agreement must be on a pose that keeps its surface out of free
  // space.
  std::optional<BaseConsensus> consensus;
  size_t keep = refined_bases;
  if (params_.instances > 1) {
    keep = static_cast<size_t>(params_.bases);
  } else if (params_.consensus_bases > 0) {
    keep = std::max(keep, static_cast<size_t>(params_.consensus_bases));
    BaseConsensus::Accept clear;
    if (free_space) {
      clear = [&](int b) {
        return free_space->violation(model, outcomes[b].pose) <= kConsensusFreeSpace;
      };
    }
    consensus.emplace(model, params_.instance_separation * model.diameter, params_.consensus_bases,
                      std::move(clear));
  }
  const auto finished = static_cast<size_t>(params_.finished_per_base);
  const int draws_per_base = std::max(1, params_.base_draw_budget / params_.bases);
  BaseDispenser dispenser(params_.bases, consensus ? &*consensus : nullptr, outcomes);
  // With no more bases than ICP candidates, every base's best is a candidate: a thread out of bases
  // begins refining those of finished bases (their first steps, firstSteps) while the other
  // threads still run theirs. At 3 bases on 2 cores one core used to run the third base alone and
  // then the third ICP screening alone. The refinements are the same whenever they run.
  const IcpRefiner* icp = indexes.icp ? &*indexes.icp : nullptr;
  const bool refine_early =
      icp && params_.instances == 1 && static_cast<size_t>(params_.bases) <= refined_bases;
  const int early_steps = icp ? firstSteps(icp->params(), static_cast<size_t>(params_.bases)) : 0;
  std::vector<std::optional<Refinement>> early(static_cast<size_t>(params_.bases));
  // Per base: 0 running or not begun, 1 finished, 2 taken for early refinement.
  std::unique_ptr<std::atomic<int>[]> base_state(new std::atomic<int>[params_.bases]());
  std::atomic<bool> early_over{false};  // some thread found nothing to take: the rest waits
#pragma omp parallel num_threads(threads)
  {
    // Best base scores of this thread (ascending, at most `keep`): scores below the K-th of them
    // cannot be among the K best overall, so verification may stop early on them.
    std::vector<float> thread_top;
    BaseSamplingScratch scratch;
    std::vector<CongruentSet> sets;
    CongruentSetMatcher::Workspace matching;
    std::vector<PlacedPose> scored;   // hypotheses of the current base
    std::vector<PartialScore> heads;  // their objectives over the first model points
    std::vector<uint32_t> order;      // the order in which they are finished
    // One draw of a base and its hypotheses (appended to `scored`); false when no base could be
    // drawn.
    auto drawBase = [&](Rng& rng, BaseWeighting weighting, BaseOutcome& out) {
      ++out.draws;
      Clock::time_point t = Clock::now();
      const std::optional<Base> base = sampler.sample(rng, scratch, weighting);
      out.stages.sampling += secondsSince(t);
      if (!base) return false;
      out.sampled = true;
      out.region = segment.region.empty() ? -1 : segment.region[(*base)[0]];

      std::array<Eigen::Vector3f, 4> bp, bn;
      for (int k = 0; k < 4; ++k) {
        bp[k] = segment.points[(*base)[k]];
        bn[k] = segment.normals[(*base)[k]];
      }
      t = Clock::now();
      matcher_.find(bp, bn, rng, sets, matching);
      out.stages.matching += secondsSince(t);
      out.sets += static_cast<int>(sets.size());

      t = Clock::now();
      for (const CongruentSet& set : sets) {
        const std::array<Eigen::Vector3f, 4> mp = {model.points[set[0]], model.points[set[1]],
                                                   model.points[set[2]], model.points[set[3]]};
        const std::optional<Eigen::Isometry3f> pose = fitRigid(mp, bp, params_.max_fit_rms);
        if (!pose) continue;
        if (!normalsAgree(scorer, *pose, set, bn)) {
          ++out.normal_mismatches;
          continue;
        }
        const PlacedPose placed{*pose, *pose * proximity_.centre()};
        if (isNearDuplicate(placed, scored)) {
          ++out.duplicates;
          continue;
        }
        scored.push_back(placed);
      }
      out.stages.verification += secondsSince(t);
      return true;
    };
    auto runBase = [&](int b) {
      if (budgeted && Clock::now() > deadline) return;
      BaseOutcome& out = outcomes[b];
      out.tried = true;
      Rng rng(streamSeed(params_.seed, static_cast<uint64_t>(b)));

      // A base with nothing to verify is drawn again from its own stream (base_draw_budget).
      scored.clear();
      const BaseWeighting weighting =
          b < params_.focused_bases ? BaseWeighting::kFocused : BaseWeighting::kSegment;
      for (int draw = 0; draw < draws_per_base && scored.empty(); ++draw) {
        if (!drawBase(rng, weighting, out)) return;
      }
      const Clock::time_point t = Clock::now();
      out.hypotheses = static_cast<long>(scored.size());
      // Heads in rounds (kHeadRounds): every hypothesis on the first share of the head, the most
      // promising of them on the next, and so on to the whole head. Then the best heads are
      // finished, best first: the base's best is found early, and the coarse checks and the exact
      // bound drop the others soon after their head. Every (partial) head covers the same model
      // points, so their objectives compare directly.
      heads.assign(scored.size(), PartialScore{});
      order.resize(scored.size());
      std::iota(order.begin(), order.end(), 0u);
      auto keepBest = [&](size_t n) {
        n = std::min(n, order.size());
        std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(n),
                          order.end(), [&](uint32_t a, uint32_t b) {
                            return heads[a].total > heads[b].total ||
                                   (heads[a].total == heads[b].total && a < b);
                          });
        order.resize(n);
      };
      for (const HeadRound& round : kHeadRounds) {
        for (uint32_t h : order) {
          scorer.extendHead(model, scored[h].pose, out.region, heads[h], round.share);
        }
        keepBest(round.width * finished);
      }
      const size_t finishing = order.size();
      out.finished = static_cast<long>(finishing);
      for (uint32_t h : order) {
        const float kth =
            thread_top.size() < keep ? -std::numeric_limits<float>::infinity() : thread_top.front();
        const float s = scorer.finishScore(model, scored[h].pose, out.region, heads[h],
                                           std::max(kth, out.score));
        if (s > out.score) {  // strict: of equal scores, the first in this order keeps it
          out.score = s;
          out.pose = scored[h].pose;
        }
      }
      out.stages.verification += secondsSince(t);
      if (out.score > -std::numeric_limits<float>::infinity()) {
        thread_top.insert(std::upper_bound(thread_top.begin(), thread_top.end(), out.score),
                          out.score);
        if (thread_top.size() > keep) thread_top.erase(thread_top.begin());
      }
    };
    for (int b; (b = dispenser.next()) >= 0;) {
      runBase(b);
      dispenser.finished(b);
      base_state[b].store(1, std::memory_order_release);
    }
    // Early refinement until nothing finished is left to take; then the others stop too, so that
    // what is left is shared out after the loop rather than run by one thread while the other
    // waits at the end of this region.
    while (refine_early && !early_over.load(std::memory_order_relaxed)) {
      int taken = -1;
      for (int b = 0; b < params_.bases && taken < 0; ++b) {
        int expected = 1;
        if (base_state[b].compare_exchange_strong(expected, 2, std::memory_order_acq_rel))
          taken = b;
      }
      if (taken < 0) {
        early_over.store(true, std::memory_order_relaxed);
        break;
      }
      const BaseOutcome& out = outcomes[static_cast<size_t>(taken)];
      if (!(out.score > 0)) continue;  // not a candidate
      const Clock::time_point t = Clock::now();
      Refinement& r = early[static_cast<size_t>(taken)].emplace(
          Hypothesis{out.pose, out.score, out.region, taken});
      refineTo(r, early_steps, model, *icp, scorer, free_space);
      outcomes[static_cast<size_t>(taken)].stages.refinement += secondsSince(t);
    }
  }
  dispenser.dropSpeculative();

  std::vector<Hypothesis> ranked;
  for (size_t b = 0; b < outcomes.size(); ++b) {
    const BaseOutcome& out = outcomes[b];
    result.bases_tried += out.tried;
    result.bases_sampled += out.sampled;
    result.base_draws += out.draws;
    result.bases_with_sets += out.sets > 0;
    result.congruent_sets += out.sets;
    result.hypotheses += out.hypotheses;
    result.duplicates += out.duplicates;
    result.normal_mismatches += out.normal_mismatches;
    result.finished += out.finished;
    result.stages.sampling += out.stages.sampling;
    result.stages.matching += out.stages.matching;
    result.stages.verification += out.stages.verification;
    result.stages.refinement += out.stages.refinement;  // begun early
    if (out.score > 0) ranked.push_back({out.pose, out.score, out.region, static_cast<int>(b)});
  }
  // Highest score first; ties go to the lower base index (stable sort over base order).
  std::stable_sort(ranked.begin(), ranked.end(), higherScore);
  if (ranked.empty()) {
    result.seconds = secondsSince(start);
    return result;
  }
  const Clock::time_point t = Clock::now();
  result.instances =
      selectInstances(ranked, refined_bases, static_cast<size_t>(params_.instances), model, scorer,
                      icp, params_, free_space, early, threads, result.icp_steps);
  if (params_.icp.enabled) result.stages.refinement += secondsSince(t);
  result.found = true;
  const InstancePose& best = result.instances.front();
  result.pose = best.pose;
  result.lcp = best.lcp;
  result.refined = best.refined;
  result.region = best.region;
  result.seconds = secondsSince(start);
  return result;
}

}  // namespace stocs
