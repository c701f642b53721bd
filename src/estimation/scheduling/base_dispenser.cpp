#include "base_dispenser.h"

namespace stocs {

BaseDispenser::BaseDispenser(int bases, BaseConsensus* consensus, Deadline deadline,
                             std::vector<BaseOutcome>& outcomes)
    : end_(bases), consensus_(consensus), deadline_(deadline), outcomes_(outcomes) {
  if (consensus_) finished_.assign(static_cast<size_t>(bases), 0);
}

int BaseDispenser::next() {
  const int b = next_.fetch_add(1, std::memory_order_relaxed);
  return b < end_.load(std::memory_order_acquire) ? b : -1;
}

bool BaseDispenser::inTime() const {
  return !deadline_ || std::chrono::steady_clock::now() <= *deadline_;
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

BaseDispenser::Deadline searchDeadline(double seconds,
                                       std::chrono::steady_clock::time_point start) {
  if (seconds <= 0) return std::nullopt;
  return start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                     std::chrono::duration<double>(seconds));
}

void BaseDispenser::dropSpeculative() {
  for (size_t b = static_cast<size_t>(end_.load()); b < outcomes_.size(); ++b) outcomes_[b] = {};
}

}  // namespace stocs
