#include "early_refinements.h"

#include <chrono>

#include "elapsed.h"

namespace stocs {

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
    out.stages.refinement += secondsSince(t);
  }
}

}  // namespace stocs
