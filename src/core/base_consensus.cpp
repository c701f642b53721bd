#include "stocs/base_consensus.h"

#include <algorithm>

namespace stocs {

BaseConsensus::BaseConsensus(const ObjectModel& model, float separation, int needed)
    : same_place_(model, separation), needed_(static_cast<size_t>(std::max(needed, 1))) {
  best_.reserve(needed_ + 1);
}

void BaseConsensus::add(int base, float score, const Eigen::Isometry3f& pose) {
  if (!(score > 0)) return;
  const auto at = std::find_if(best_.begin(), best_.end(), [&](const Entry& e) {
    return score > e.score || (score == e.score && base < e.base);
  });
  if (static_cast<size_t>(at - best_.begin()) >= needed_) return;
  if (at == best_.begin()) {
    for (Entry& e : best_) e.agrees = -1;  // a new best: every agreement is to be tested again
  }
  best_.insert(at, Entry{score, base, pose, -1});
  if (best_.size() > needed_) best_.pop_back();
}

bool BaseConsensus::reached() {
  if (best_.size() < needed_) return false;
  for (Entry& e : best_) {
    if (e.agrees < 0) {
      e.agrees = &e == &best_.front() || same_place_.samePlace(e.pose, best_.front().pose);
    }
    if (!e.agrees) return false;
  }
  return true;
}

}  // namespace stocs
