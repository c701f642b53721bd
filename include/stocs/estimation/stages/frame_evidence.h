#pragma once
// What a frame says about a pose beyond the segment's shape: the measured surface (where the
// camera sees past the pose's surface) and, later stages add, the colour. It tells a pose from its
// shape alternatives (StocsEstimator::search).

#include "stocs/estimation/stages/free_space_check.h"

namespace stocs {

/// Any member may be null: that evidence is absent.
struct FrameEvidence {
  const FreeSpaceCheck* surface = nullptr;
};

}  // namespace stocs
