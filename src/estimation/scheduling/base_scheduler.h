#pragma once
// How the threads share an estimate's work: the bases in index order with the consensus stop
// between blocks (BaseDispenser), and, with few bases, the refinement of finished bases' poses by a
// thread that has run out of bases (EarlyRefinements).

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "stages/base_verification.h"
#include "stages/candidate_refinement.h"
#include "stocs/estimation/scheduling/base_consensus.h"

namespace stocs {

/// Hands out the bases to the threads in index order and runs the consensus stop between blocks
/// without a barrier: whoever completes the last outstanding base of a block checks it (blocks in
/// order), while the other threads go on with the next bases. Once a block reaches consensus, no
/// base after it starts, and those already started are dropped (dropSpeculative), so the result
/// is that of the bases up to that block for every thread count. A thread takes bases in
/// increasing order, so its pruning bound (the best scores it has seen) only ever holds bases of
/// lower index than the one it verifies: a dropped base never changes a kept one.
class BaseDispenser {
 public:
  BaseDispenser(int bases, BaseConsensus* consensus, std::vector<BaseOutcome>& outcomes);

  /// The next base to run, or -1 when none is left.
  int next();
  /// Base `b` has run (its outcome is written): check the blocks it completes.
  void finished(int b);
  /// After the threads are done: clears the outcomes of bases started after the consensus.
  void dropSpeculative();

 private:
  std::atomic<int> next_{0};
  std::atomic<int> end_;  // bases from here on do not count
  BaseConsensus* consensus_;
  std::vector<BaseOutcome>& outcomes_;
  std::mutex mutex_;
  std::vector<char> finished_;  // per base, under mutex_
  int complete_ = 0;            // bases before it have all finished, under mutex_
};

/// With no more bases than ICP candidates, every base's best is a candidate: a thread out of bases
/// begins refining those of finished bases (their first steps, firstSteps) while the other threads
/// still run theirs, rather than idle while one core runs the last base alone and then its ICP
/// screening alone. The refinements are the same whenever they run.
class EarlyRefinements {
 public:
  /// Off (nothing is refined early) unless `enabled`; `steps` are the steps each one takes.
  EarlyRefinements(int bases, bool enabled, int steps);

  /// Base `b` has run: its best may be refined.
  void finished(int b) { state_[b].store(kFinished, std::memory_order_release); }
  /// Refines finished bases' poses until none is left to take; then the other threads stop too,
  /// so that what is left is shared out after the loop rather than run by one thread while the
  /// others wait. Adds the time to the bases' refinement stage.
  void work(std::vector<BaseOutcome>& outcomes, const RefinementContext& context);
  /// Per base, the refinement begun (empty where none was).
  std::vector<std::optional<Refinement>>& begun() { return begun_; }

 private:
  static constexpr int kRunning = 0, kFinished = 1, kTaken = 2;
  /// A finished base not yet taken, now taken, or -1.
  int take();

  int bases_;
  bool enabled_;
  int steps_;
  std::vector<std::optional<Refinement>> begun_;
  std::unique_ptr<std::atomic<int>[]> state_;  // per base: kRunning (or not begun), ...
  std::atomic<bool> over_{false};              // some thread found nothing to take
};

}  // namespace stocs
