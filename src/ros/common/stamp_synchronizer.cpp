#include "stocs_ros/common/stamp_synchronizer.h"

#include <fmt/format.h>

#include "stocs/util/error.h"

namespace stocs_ros {

const stocs::ParamSet<SyncParams>& SyncParams::schema() {
  static const stocs::ParamSet<SyncParams> schema =
      stocs::ParamSet<SyncParams>()
          .add(&SyncParams::tolerance, "tolerance", "s", stocs::ParamRange::closed(0, 10),
               "between the reference (cloud or depth) stamp and the stamps matched to it")
          .add(&SyncParams::queue_size, "queue_size", "", stocs::ParamRange::closed(1, 1000),
               "messages kept per input while waiting for a match")
          .add(&SyncParams::max_age, "max_age", "s", stocs::ParamRange::closed(0, 3600),
               "behind the newest stamp before a message is dropped; 0: never");
  return schema;
}

void SyncParams::validate() const {
  schema().validate(*this);
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
