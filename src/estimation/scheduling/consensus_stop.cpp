#include "consensus_stop.h"

#include <utility>

namespace stocs {
namespace {

/// The consensus stop's free-space limit: the best base's pose may put at most this share of its
/// camera-facing surface where the sensor sees through. The wrong poses that agreement alone stops
/// on (slid boxes, turned-over blocks) put far more there; objects whose best raw pose exceeds the
/// limit just run every base. The unrefined pose is judged: ICP also pulls wrong poses out of
/// free space.
constexpr float kConsensusFreeSpace = 0.05f;

}  // namespace

std::optional<BaseConsensus> consensusStop(const ObjectModel& model, const StocsParams& params,
                                           const FreeSpaceCheck* free_space,
                                           const std::vector<BaseOutcome>& outcomes) {
  if (params.instances > 1 || params.consensus_bases == 0) return std::nullopt;
  BaseConsensus::Accept clear;
  if (free_space) {
    clear = [free_space, &outcomes, &model](int b) {
      return free_space->violation(model, outcomes[b].pose) <= kConsensusFreeSpace;
    };
  }
  return std::make_optional<BaseConsensus>(model, params.instance_separation * model.diameter,
                                           params.consensus_bases, std::move(clear));
}

}  // namespace stocs
