#include "stocs/estimation/scheduling/base_consensus.h"

#include <algorithm>
#include <utility>

#include "stocs/estimation/stages/pose_confidence.h"

namespace stocs {

namespace {

/// Model points of the same-place test: a pose that agrees with the best costs a closest-point
/// query per point, in the single-threaded pause between blocks, so it compares fewer points than
/// the separation of instances (InstanceSeparation's default).
constexpr size_t kProbePoints = 64;

}  // namespace

BaseConsensus::BaseConsensus(const ObjectModel& model, float separation, int needed, Accept accept)
    : same_place_(model, separation, kProbePoints),
      accept_(std::move(accept)),
      needed_(static_cast<size_t>(std::max(needed, 1))) {
  best_.reserve(needed_ + 1);
}

void BaseConsensus::add(int base, float score, const Eigen::Isometry3f& pose) {
  if (!(score > 0)) return;
  const auto at = std::find_if(best_.begin(), best_.end(), [&](const Entry& e) {
    return score > e.score || (score == e.score && base < e.base);
  });
  if (static_cast<size_t>(at - best_.begin()) >= needed_) return;
  if (at == best_.begin()) {  // a new best: everything is to be tested again
    for (Entry& e : best_) e.agrees = -1;
    best_accepted_ = -1;
  }
  best_.insert(at, Entry{score, base, pose, -1});
  if (best_.size() > needed_) best_.pop_back();
}

float consensusShare(const Eigen::Isometry3f& pose,
                     const std::vector<Eigen::Isometry3f>& base_poses,
                     const InstanceSeparation& same_place, const Eigen::Vector3f& centre,
                     float separation) {
  const int needed = ConfidenceEvidence::kConsensusBases;
  const Eigen::Vector3f at = pose * centre;
  int agree = 0;
  for (size_t i = 0; i < base_poses.size() && agree < needed; ++i) {
    if ((base_poses[i] * centre - at).norm() >= separation) continue;
    agree += same_place.samePlace(pose, base_poses[i]);
  }
  return static_cast<float>(agree) / static_cast<float>(needed);
}

bool BaseConsensus::reached() {
  if (best_.size() < needed_) return false;
  for (Entry& e : best_) {
    if (e.agrees < 0) {
      e.agrees = &e == &best_.front() || same_place_.samePlace(e.pose, best_.front().pose);
    }
    if (!e.agrees) return false;
  }
  if (best_accepted_ < 0) best_accepted_ = !accept_ || accept_(best_.front().base);
  return best_accepted_;
}

}  // namespace stocs
