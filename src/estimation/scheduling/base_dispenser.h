#pragma once
// How the threads share the base loop: the bases in index order, the consensus stop between
// blocks of them, and the time budget.

#include <atomic>
#include <chrono>
#include <mutex>
#include <optional>
#include <vector>

#include "stages/base_verification.h"
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
  using Deadline = std::optional<std::chrono::steady_clock::time_point>;

  /// A base handed out after `deadline` (StocsParams::time_budget), when there is one, is not run.
  BaseDispenser(int bases, BaseConsensus* consensus, Deadline deadline,
                std::vector<BaseOutcome>& outcomes);

  /// The next base, or -1 when none is left.
  int next();
  /// Whether the base just handed out may run: the deadline has not passed. A base that may not
  /// is still reported finished, with its outcome left empty.
  bool inTime() const;
  /// Base `b` has run (its outcome is written): check the blocks it completes.
  void finished(int b);
  /// After the threads are done: clears the outcomes of bases started after the consensus.
  void dropSpeculative();

 private:
  std::atomic<int> next_{0};
  std::atomic<int> end_;  // bases from here on do not count
  BaseConsensus* consensus_;
  Deadline deadline_;
  std::vector<BaseOutcome>& outcomes_;
  std::mutex mutex_;
  std::vector<char> finished_;  // per base, under mutex_
  int complete_ = 0;            // bases before it have all finished, under mutex_
};

/// The end of a search's time budget of `seconds` from `start` (none for 0).
BaseDispenser::Deadline searchDeadline(double seconds, std::chrono::steady_clock::time_point start);

}  // namespace stocs
