#pragma once
// With few bases, the refinement of finished bases' poses by a thread that has run out of bases.

#include <atomic>
#include <memory>
#include <optional>
#include <vector>

#include "stages/base_verification.h"
#include "stages/candidate_refinement.h"

namespace stocs {

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
