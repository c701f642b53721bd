#pragma once
// The search's adaptive end (StocsParams::consensus_bases): BaseConsensus over the bases' best
// poses, with the free-space check of the best one when the frame gives it.

#include <optional>
#include <vector>

#include "stages/base_verification.h"
#include "stocs/estimation/scheduling/base_consensus.h"
#include "stocs/estimation/stages/free_space_check.h"

namespace stocs {

/// The consensus stop of a search for `model` with `params` over the bases' `outcomes`, or none:
/// a search for several instances runs every base, since the next instance may come from any.
/// With `free_space`, agreement must be on a pose that keeps its surface out of free space.
std::optional<BaseConsensus> consensusStop(const ObjectModel& model, const StocsParams& params,
                                           const FreeSpaceCheck* free_space,
                                           const std::vector<BaseOutcome>& outcomes);

}  // namespace stocs
