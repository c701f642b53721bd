#include "stocs_ros/stamp_synchronizer.h"

#include <fmt/format.h>

#include "stocs/error.h"

namespace stocs_ros {

void SyncParams::validate() const {
  if (!(tolerance >= 0 && tolerance <= 10)) {
    throw stocs::InputError(fmt::format("tolerance {} s is outside [0, 10]", tolerance));
  }
  if (queue_size < 1 || queue_size > 1000) {
    throw stocs::InputError(fmt::format("queue_size {} is outside [1, 1000]", queue_size));
  }
  if (!(max_age >= 0 && max_age <= 3600)) {
    throw stocs::InputError(fmt::format("max_age {} s is outside [0, 3600]", max_age));
  }
}

const char* toString(DropReason reason) {
  switch (reason) {
    case DropReason::kQueueFull:
      return "queue full";
    case DropReason::kUnmatched:
      return "unmatched (a newer frame was complete first)";
    case DropReason::kLate:
      return "late (stamp at or before a frame matched before it arrived)";
    case DropReason::kTooOld:
      return "too old (beyond max_age)";
    case DropReason::kTimeJump:
      return "time jump (waiting for a frame from before time went back)";
  }
  return "unknown";
}

const char* shortName(DropReason reason) {
  static constexpr const char* kShort[kDropReasonCount] = {"queue full", "unmatched", "late",
                                                           "too old", "time jump"};
  return kShort[static_cast<size_t>(reason)];
}

std::string describeDropCounts(const std::array<uint64_t, kDropReasonCount>& counts) {
  std::string out;
  for (size_t r = 0; r < kDropReasonCount; ++r) {
    if (counts[r] > 0) {
      out += fmt::format("{}{} {}", out.empty() ? "" : ", ", counts[r],
                         shortName(static_cast<DropReason>(r)));
    }
  }
  return out.empty() ? "none" : out;
}

}  // namespace stocs_ros
