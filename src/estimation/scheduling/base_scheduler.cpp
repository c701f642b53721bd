#include "base_scheduler.h"

#include <chrono>

namespace stocs {

BaseDispenser::BaseDispenser(int bases, BaseConsensus* consensus,
                             std::vector<BaseOutcome>& outcomes)
    : end_(bases), consensus_(consensus), outcomes_(outcomes) {
  if (consensus_) finished_.assign(static_cast<size_t>(bases), 0);
}

int BaseDispenser::next() {
  const int b = next_.fetch_add(1, std::memory_order_relaxed);
  return b < end_.load(std::memory_order_acquire) ? b : -1;
}

void BaseDispenser::finished(int b) {
  if (!consensus_) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  finished_[static_cast<size_t>(b)] = 1;
  const int end = end_.load(std::memory_order_relaxed);
  while (complete_ < end && finished_[static_cast<size_t>(complete_)]) {
    const BaseOutcome& out = outcomes_[static_cast<size_t>(complete_)];
    consensus_->add(complete_, out.score, out.pose);
    ++complete_;
    if (complete_ % StocsParams::kConsensusBlock == 0 && complete_ < end && consensus_->reached()) {
      end_.store(complete_, std::memory_order_release);
      return;
    }
  }
}

void BaseDispenser::dropSpeculative() {
  for (size_t b = static_cast<size_t>(end_.load()); b < outcomes_.size(); ++b) outcomes_[b] = {};
}

EarlyRefinements::EarlyRefinements(int bases, bool enabled, int steps)
    : bases_(bases),
      enabled_(enabled),
      steps_(steps),
      begun_(static_cast<size_t>(bases)),
      state_(new std::atomic<int>[static_cast<size_t>(bases)]()) {}

int EarlyRefinements::take() {
  for (int b = 0; b < bases_; ++b) {
    int expected = kFinished;
    if (state_[b].compare_exchange_strong(expected, kTaken, std::memory_order_acq_rel)) return b;
  }
  return -1;
}

void EarlyRefinements::work(std::vector<BaseOutcome>& outcomes, const RefinementContext& context) {
  while (enabled_ && !over_.load(std::memory_order_relaxed)) {
    const int taken = take();
    if (taken < 0) {
      over_.store(true, std::memory_order_relaxed);
      break;
    }
    BaseOutcome& out = outcomes[static_cast<size_t>(taken)];
    if (!(out.score > 0)) continue;  // not a candidate
    const auto t = std::chrono::steady_clock::now();
    Refinement& r = begun_[static_cast<size_t>(taken)].emplace(
        Hypothesis{out.pose, out.score, out.region, taken});
    refineTo(r, steps_, context);
    out.stages.refinement +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  }
}

}  // namespace stocs
