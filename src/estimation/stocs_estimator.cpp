#include "stocs/estimation/stocs_estimator.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <optional>
#include <vector>

#include "elapsed.h"
#include "scheduling/base_dispenser.h"
#include "scheduling/consensus_stop.h"
#include "scheduling/early_refinements.h"
#include "stages/alternative_choice.h"
#include "stages/base_verification.h"
#include "stages/candidate_refinement.h"
#include "stocs/estimation/instance_separation.h"
#include "stocs/estimation/scheduling/base_consensus.h"

namespace stocs {
namespace {

using Clock = std::chrono::steady_clock;

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

/// Adds the counters and stage times of every base to `result`, and returns the bases' best
/// hypotheses, highest score first (ties to the lower base index).
std::vector<Hypothesis> rankBases(const std::vector<BaseOutcome>& outcomes, PoseEstimate& result) {
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
  std::stable_sort(ranked.begin(), ranked.end(), higherScore);
  return ranked;
}

/// Keeps the bases' poses (best first) in the estimate and sets each instance's consensus evidence
/// from them (consensusShare).
void addConsensus(const ObjectModel& model, const Eigen::Vector3f& centre, float separation,
                  const std::vector<Hypothesis>& ranked, PoseEstimate& estimate) {
  estimate.base_poses.clear();
  for (const Hypothesis& h : ranked) estimate.base_poses.push_back(h.pose);
  const InstanceSeparation same_place(model, separation);
  for (InstancePose& instance : estimate.instances) {
    instance.evidence.consensus =
        consensusShare(instance.pose, estimate.base_poses, same_place, centre, separation);
  }
}

}  // namespace

const ParamSet<StocsParams>& StocsParams::schema() {
  static const ParamSet<StocsParams> schema =
      ParamSet<StocsParams>()
          .nest(&StocsParams::base, "base", BaseSamplerParams::schema())
          .nest(&StocsParams::congruent, "congruent", CongruentSetParams::schema())
          .add(&StocsParams::max_fit_rms, "max_fit_rms", "m", ParamRange::aboveUpTo(0, 0.1),
               "congruent sets whose rigid fit is worse are dropped")
          .flag("--fit-rms")
          .add(&StocsParams::duplicate_distance, "duplicate_distance", "m",
               ParamRange::closed(0, 0.1),
               "hypotheses of one base this close to a scored one are skipped")
          .add(&StocsParams::min_normal_agreement, "min_normal_agreement", "",
               ParamRange::closed(0, 4),
               "base points whose normal must agree (delta_n) for a fit to be scored")
          .flag("--min-normal-agreement")
          .add(&StocsParams::finished_per_base, "finished_per_base", "",
               ParamRange::closed(1, 100000),
               "hypotheses of a base scored in full: those best on the first coarse share")
          .flag("--finished-per-base")
          .nest(&StocsParams::lcp, "lcp", LcpParams::schema())
          .nest(&StocsParams::icp, "icp", IcpParams::schema())
          .nest(&StocsParams::free_space, "free_space", FreeSpaceParams::schema())
          .add(&StocsParams::bases, "bases", "", ParamRange::closed(1, 1000000),
               "bases per object (at most, with consensus_bases)")
          .flag("--bases")
          .add(&StocsParams::base_draw_budget, "base_draw_budget", "",
               ParamRange::closed(0, 1000000),
               "a base with nothing to verify is drawn again, up to budget / bases draws")
          .flag("--draw-budget")
          .add(&StocsParams::focused_bases, "focused_bases", "", ParamRange::closed(0, 1000000),
               "the first bases draw by pi_k^focus_exponent, the rest by pi_k; 0: never")
          .flag("--focused-bases")
          .add(&StocsParams::consensus_bases, "consensus_bases", "", ParamRange::closed(0, 1000),
               "stop between blocks of 10 bases once this many best bases agree; 0: never")
          .flag("--consensus")
          .add(&StocsParams::time_budget, "time_budget", "s", ParamRange::closed(0, 3600),
               "per object; 0: no limit (a budget makes results machine-dependent)")
          .flag("--time-budget")
          .add(&StocsParams::seed, "seed", "", std::nullopt, "random seed")
          .flag("--seed")
          .add(&StocsParams::threads, "threads", "", ParamRange::closed(0, 256),
               "threads per object; 0: all cores (results do not depend on it)")
          .flag("--threads")
          .add(&StocsParams::instances, "instances", "", ParamRange::closed(1, 100),
               "poses per object (a bin of identical objects): frames <object>_<k>")
          .flag("--instances")
          .add(&StocsParams::instance_separation, "instance_separation", "",
               ParamRange::aboveUpTo(0, 1),
               "two poses are one instance below this ADD-S, fraction of the diameter")
          .flag("--instance-separation")
          .add(&StocsParams::shape_alternatives, "shape_alternatives",
               "judge each pose against the model's near-symmetric turns (free space, colour)")
          .flag("--shape-alternatives");
  return schema;
}

void StocsParams::validate() const {
  schema().validate(*this);
}

StocsEstimator::StocsEstimator(const PreparedModel& model, const StocsParams& params)
    : model_(model),
      params_((params.validate(), params)),
      matcher_(model, params.congruent),
      proximity_(model.model) {}

size_t StocsEstimator::refinedBases() const {
  return params_.icp.enabled ? static_cast<size_t>(params_.icp.candidates) : 1;
}

size_t StocsEstimator::keptScores() const {
  // The K best bases go on to refinement, so a hypothesis matters when it can still beat its own
  // base's best and the K-th best base score seen so far. Several instances need every base's
  // best, as the next instance may come from any base; the consensus stop needs exact scores for
  // the bases it compares.
  if (params_.instances > 1) return static_cast<size_t>(params_.bases);
  if (params_.consensus_bases > 0) {
    return std::max(refinedBases(), static_cast<size_t>(params_.consensus_bases));
  }
  return refinedBases();
}

std::vector<BaseOutcome> StocsEstimator::runBases(const SoftSegment& segment,
                                                  const LcpScorer& scorer,
                                                  const FreeSpaceCheck* free_space,
                                                  const RefinementContext& refinement,
                                                  EarlyRefinements& early, int threads,
                                                  Clock::time_point start) const {
  const BaseSampler sampler(segment, model_.ppf_map, params_.base);
  const BaseStages stages{segment,      sampler,    matcher_, scorer,
                          model_.model, proximity_, params_,  keptScores()};
  std::vector<BaseOutcome> outcomes(static_cast<size_t>(params_.bases));
  std::optional<BaseConsensus> stop = consensusStop(model_.model, params_, free_space, outcomes);
  BaseDispenser dispenser(params_.bases, stop ? &*stop : nullptr,
                          searchDeadline(params_.time_budget, start), outcomes);
#pragma omp parallel num_threads(threads)
  {
    BaseVerifier verifier(stages);
    for (int b; (b = dispenser.next()) >= 0;) {
      if (dispenser.inTime()) verifier.run(b, outcomes[static_cast<size_t>(b)]);
      dispenser.finished(b);
      early.finished(b);
    }
    early.work(outcomes, refinement);
  }
  dispenser.dropSpeculative();
  return outcomes;
}

PoseEstimate StocsEstimator::search(const SoftSegment& segment, const FreeSpaceCheck* free_space,
                                    const FrameEvidence& evidence) const {
  const Clock::time_point start = Clock::now();
  PoseEstimate result;
  if (segment.size() < 4) {
    result.seconds = secondsSince(start);
    return result;
  }
  const int threads = params_.threads > 0 ? params_.threads : omp_get_max_threads();
  SegmentIndexes indexes;
  buildIndexes(segment, params_, threads, indexes);
  const IcpRefiner* icp = indexes.icp ? &*indexes.icp : nullptr;
  const RefinementContext refinement{model_.model, model_.near_symmetries, icp, *indexes.scorer,
                                     free_space};
  EarlyRefinements early(
      params_.bases,
      icp && params_.instances == 1 && static_cast<size_t>(params_.bases) <= refinedBases(),
      icp ? firstSteps(icp->params(), static_cast<size_t>(params_.bases)) : 0);

  // Algorithm 1's loop: every base drawn (Algorithm 2), its congruent sets found, each fitted and
  // scored by the objective f; each base keeps its best hypothesis (BaseVerifier).
  const std::vector<BaseOutcome> outcomes =
      runBases(segment, *indexes.scorer, free_space, refinement, early, threads, start);
  const std::vector<Hypothesis> ranked = rankBases(outcomes, result);
  if (ranked.empty()) {
    result.seconds = secondsSince(start);
    return result;
  }
  // Its T_opt, refined: the best bases refined, the best refined pose (and further distinct
  // instances) returned.
  const Clock::time_point t = Clock::now();
  result.instances =
      selectInstances(ranked, refinedBases(), static_cast<size_t>(params_.instances), refinement,
                      params_.instance_separation, early.begun(), threads, result.icp_steps);
  if (params_.shape_alternatives) {
    chooseAmongAlternatives(result.instances, model_, segment, refinement, evidence, threads,
                            result.icp_steps);
  }
  if (params_.icp.enabled) result.stages.refinement += secondsSince(t);
  addConsensus(model_.model, proximity_.centre(),
               params_.instance_separation * model_.model.diameter, ranked, result);
  result.seconds = secondsSince(start);
  return result;
}

}  // namespace stocs
