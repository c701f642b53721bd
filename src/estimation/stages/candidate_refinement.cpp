#include "candidate_refinement.h"

#include <algorithm>
#include <numeric>

#include "stocs/estimation/instance_separation.h"
#include "stocs/estimation/stages/pose_covariance.h"

namespace stocs {
namespace {

/// `h` after point-to-plane refinement to `refined`: the refined pose is kept when it does not
/// lower the objective by more than 10% (a diverged refinement keeps the unrefined pose); then,
/// with a free-space check, the score is discounted by the share of the pose's visible surface in
/// free space.
Hypothesis judged(const Hypothesis& h, const Eigen::Isometry3f* refined,
                  const RefinementContext& c) {
  Hypothesis out = h;
  out.polished = true;
  if (refined) {
    const float score = c.scorer.score(c.model, *refined, h.region);
    if (score >= 0.9f * h.score) {
      out.pose = *refined;
      out.score = score;
      out.refined = !refined->isApprox(h.pose);
    }
  }
  if (c.free_space) out.score *= 1.0f - c.free_space->violation(c.model, out.pose);
  return out;
}

/// `h` refined to the end (or only judged without ICP); adds the ICP steps taken to `steps`.
Hypothesis refine(const Hypothesis& h, const RefinementContext& c, long& steps) {
  if (!c.icp) return judged(h, nullptr, c);
  Refinement r(h);
  refineTo(r, c.icp->params().iterations, c);
  steps += r.run.iterations;
  return *r.judged;
}

/// The `first` best of `ranked` refined, in parallel: each refinement is independent and reads only
/// shared const state. With `screen`, every candidate first takes firstSteps() steps, and only the
/// IcpParams::finalists best of them by the judged objective take the others: a candidate's first
/// steps settle whether it is in the running, and most of the ICP time would go into the later
/// steps of candidates that then lose. When several instances are wanted every candidate may be
/// one, and all are refined to the end. `early`, per base, holds refinements that the base loop
/// began (their first steps taken); the others begin here. Adds the ICP steps taken to `steps`.
std::vector<Hypothesis> refineCandidates(const std::vector<Hypothesis>& ranked, size_t first,
                                         bool screen, const RefinementContext& c,
                                         std::vector<std::optional<Refinement>>& early, int threads,
                                         long& steps) {
  std::vector<Hypothesis> pool(ranked.begin(), ranked.begin() + static_cast<std::ptrdiff_t>(first));
  if (!c.icp) {
    for (size_t k = 0; k < first; ++k) pool[k] = refine(ranked[k], c, steps);
    return pool;
  }
  const IcpParams& params = c.icp->params();
  const int first_steps = screen ? firstSteps(params, first) : params.iterations;
  std::vector<Refinement> runs;
  runs.reserve(first);
  for (size_t k = 0; k < first; ++k) {
    std::optional<Refinement>& begun = early[static_cast<size_t>(ranked[k].base)];
    runs.push_back(begun ? std::move(*begun) : Refinement(ranked[k]));
  }
  auto runTo = [&](size_t k, int until) {
    refineTo(runs[k], until, c);
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

}  // namespace

int firstSteps(const IcpParams& icp, size_t candidates) {
  const bool screening = icp.screening_iterations > 0 &&
                         icp.screening_iterations < icp.iterations &&
                         candidates > static_cast<size_t>(icp.finalists);
  return screening ? icp.screening_iterations : icp.iterations;
}

void refineTo(Refinement& r, int steps, const RefinementContext& c) {
  if (r.judged && (r.run.finished || r.run.iterations >= steps)) return;
  c.icp->iterate(c.model, r.run, steps, r.start.region, &c.scorer);
  r.judged = judged(r.start, &r.run.pose, c);
}

std::vector<InstancePose> selectInstances(const std::vector<Hypothesis>& ranked,
                                          size_t refined_bases, size_t count,
                                          const RefinementContext& c, float instance_separation,
                                          std::vector<std::optional<Refinement>>& early,
                                          int threads, long& steps) {
  const size_t first = std::min(refined_bases, ranked.size());
  std::vector<Hypothesis> pool =
      refineCandidates(ranked, first, count == 1, c, early, threads, steps);
  std::stable_sort(pool.begin(), pool.end(), higherScore);
  pool.insert(pool.end(), ranked.begin() + static_cast<std::ptrdiff_t>(first), ranked.end());

  std::optional<InstanceSeparation> separation;
  if (count > 1) separation.emplace(c.model, instance_separation * c.model.diameter);
  std::vector<Hypothesis> taken;
  auto isNew = [&](const Hypothesis& h) {
    return std::none_of(taken.begin(), taken.end(),
                        [&](const Hypothesis& t) { return separation->samePlace(h.pose, t.pose); });
  };
  for (Hypothesis h : pool) {
    if (taken.size() == count) break;
    if (!taken.empty() && !isNew(h)) continue;
    if (!h.polished) {
      h = refine(h, c, steps);
      if (!taken.empty() && !isNew(h)) continue;  // refinement moved it onto a taken instance
    }
    taken.push_back(h);
  }
  std::stable_sort(taken.begin(), taken.end(), higherScore);
  std::vector<InstancePose> instances;
  for (const Hypothesis& h : taken) {
    InstancePose& instance = instances.emplace_back();
    instance.pose = h.pose;
    instance.lcp = c.scorer.detail(c.model, h.pose, h.region);
    instance.score = instance.lcp.score;
    instance.refined = h.refined;
    instance.region = h.region;
    instance.covariance =
        poseCovariance(c.model, c.icp, h.pose, h.region, &c.scorer, c.near_symmetries);
  }
  return instances;
}

}  // namespace stocs
