#include "stocs/stocs_estimator.h"

#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <limits>
#include <vector>

#include "stocs/error.h"
#include "stocs/rigid_fit.h"

namespace stocs {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

/// What one base produced: its best hypothesis and counters.
struct BaseOutcome {
  bool tried = false, sampled = false;
  int sets = 0;
  long hypotheses = 0;
  float score = -std::numeric_limits<float>::infinity();
  int region = -1;  // instance region of the base, -1 without regions
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  StageSeconds stages;
};

}  // namespace

void StocsParams::validate() const {
  base.validate();
  congruent.validate();
  lcp.validate();
  icp.validate();
  if (!(max_fit_rms > 0.0f && max_fit_rms <= 0.1f)) {
    throw InputError(fmt::format("rigid fit RMS limit {} m is outside (0, 0.1]", max_fit_rms));
  }
  if (bases < 1 || bases > 1000000)
    throw InputError(fmt::format("bases {} is outside [1, 1000000]", bases));
  if (!(time_budget >= 0) || time_budget > 3600) {
    throw InputError(fmt::format("time budget {} s is outside [0, 3600]", time_budget));
  }
  if (threads < 0 || threads > 256)
    throw InputError(fmt::format("threads {} is outside [0, 256]", threads));
}

StocsEstimator::StocsEstimator(const PreparedModel& model, const StocsParams& params)
    : model_(model), params_(params), matcher_(model, params.congruent) {
  params_.validate();
}

PoseEstimate StocsEstimator::estimate(const SoftSegment& segment) const {
  const Clock::time_point start = Clock::now();
  PoseEstimate result;
  if (segment.size() < 4) {
    result.seconds = secondsSince(start);
    return result;
  }
  const BaseSampler sampler(segment, model_.ppf_map, params_.base);
  const LcpScorer scorer(segment, params_.lcp);
  const ObjectModel& model = model_.model;
  const bool budgeted = params_.time_budget > 0;
  const Clock::time_point deadline =
      start + std::chrono::duration_cast<Clock::duration>(
                  std::chrono::duration<double>(params_.time_budget));

  std::vector<BaseOutcome> outcomes(params_.bases);
  const int threads = params_.threads > 0 ? params_.threads : omp_get_max_threads();
#pragma omp parallel num_threads(threads)
  {
    // Scores below the best this thread has seen cannot win; verification may stop early on them.
    float thread_best = -std::numeric_limits<float>::infinity();
    std::vector<std::pair<int, float>> scratch;
    std::vector<CongruentSet> sets;
#pragma omp for schedule(dynamic, 1)
    for (int b = 0; b < params_.bases; ++b) {
      if (budgeted && Clock::now() > deadline) continue;
      BaseOutcome& out = outcomes[b];
      out.tried = true;
      Rng rng(streamSeed(params_.seed, static_cast<uint64_t>(b)));

      Clock::time_point t = Clock::now();
      const std::optional<Base> base = sampler.sample(rng, scratch);
      out.stages.sampling = secondsSince(t);
      if (!base) continue;
      out.sampled = true;
      out.region = segment.region.empty() ? -1 : segment.region[(*base)[0]];

      std::array<Eigen::Vector3f, 4> bp, bn;
      for (int k = 0; k < 4; ++k) {
        bp[k] = segment.points[(*base)[k]];
        bn[k] = segment.normals[(*base)[k]];
      }
      t = Clock::now();
      matcher_.find(bp, bn, rng, sets);
      out.stages.matching = secondsSince(t);
      out.sets = static_cast<int>(sets.size());

      t = Clock::now();
      for (const CongruentSet& set : sets) {
        const std::array<Eigen::Vector3f, 4> mp = {model.points[set[0]], model.points[set[1]],
                                                   model.points[set[2]], model.points[set[3]]};
        const std::optional<Eigen::Isometry3f> pose = fitRigid(mp, bp, params_.max_fit_rms);
        if (!pose) continue;
        ++out.hypotheses;
        const float s = scorer.score(model, *pose, out.region, thread_best);
        if (s > out.score) {  // strict: the first set reaching a score keeps it
          out.score = s;
          out.pose = *pose;
        }
        thread_best = std::max(thread_best, s);
      }
      out.stages.verification = secondsSince(t);
    }
  }

  // Reduce in base order: the highest score wins, ties go to the lower base index.
  const BaseOutcome* best = nullptr;
  for (const BaseOutcome& out : outcomes) {
    result.bases_tried += out.tried;
    result.bases_sampled += out.sampled;
    result.bases_with_sets += out.sets > 0;
    result.congruent_sets += out.sets;
    result.hypotheses += out.hypotheses;
    result.stages.sampling += out.stages.sampling;
    result.stages.matching += out.stages.matching;
    result.stages.verification += out.stages.verification;
    if (out.score > 0 && (!best || out.score > best->score)) best = &out;
  }
  if (best) {
    result.found = true;
    result.pose = best->pose;
    result.region = best->region;
    if (params_.icp.enabled) {
      const Clock::time_point t = Clock::now();
      const Eigen::Isometry3f refined =
          refinePointToPlane(model, segment, best->pose, best->region, params_.icp);
      if (scorer.score(model, refined, best->region) >= 0.9f * best->score) {
        result.pose = refined;
        result.refined = !refined.isApprox(best->pose);
      }
      result.stages.refinement = secondsSince(t);
    }
    result.lcp = scorer.detail(model, result.pose, best->region);
  }
  result.seconds = secondsSince(start);
  return result;
}

}  // namespace stocs
