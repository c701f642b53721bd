#pragma once
// What the node did with every input message and every frame, so that nothing is dropped without
// a counted reason. Per input: messages received, dropped by the synchronizer (by reason) and still
// waiting in it. Per synchronized frame: estimated and published, replaced by a newer frame before
// its estimation started, rejected (by the input at fault), kept for ~estimate only
// (output.estimate_on_frames: false), or still in progress. Hence, per input,
//   received = matched + dropped + queued,   matched = estimated + replaced + rejected + kept +
//   in progress.
// Per estimated frame or service call, the poses published and those rejected for a low confidence
// (not published; see RejectedObject.msg); with tracking, the instances tracked, redetected and
// lost, the full detections and the restarts of the tracks.
// Published as diagnostic_msgs/DiagnosticStatus key-value pairs and logged at shutdown.
// Thread-safe: subscription callbacks, the worker and the service thread all count.

#include <diagnostic_msgs/DiagnosticStatus.h>

#include <array>
#include <cstdint>
#include <exception>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "stocs/tracking/frame_tracker.h"
#include "stocs_ros/common/stamp_synchronizer.h"

namespace stocs_ros {

/// Seconds between repeats of one kind of throttled warning or error; ~statistics counts them all.
inline constexpr double kWarnPeriod = 5.0;

/// The input a rejected frame's error names ("cloud", "probability image of 'box'", ...: the text
/// before the first ": " of a stocs::InputError), or "internal error" for any other exception.
std::string rejectionKind(std::exception_ptr error);

class NodeStatistics {
 public:
  /// `topics`: the inputs' resolved topic names, in the synchronizer's input order.
  explicit NodeStatistics(std::vector<std::string> topics);

  void received(size_t input);
  void dropped(const std::vector<DroppedMessage>& messages);
  void matched();
  void kept();
  void replaced();
  void estimated();
  void rejected(const std::string& kind);
  /// A result's poses: `published` accepted ones, `rejected` ones below min_confidence.
  void poses(size_t published, size_t rejected);
  void serviceCall(bool success);
  /// Time went back and the synchronizer started again (see stamp_synchronizer.h).
  void timeJumpedBack();
  /// A tracked frame's instances by state, its full detections and whether the tracks restarted.
  void tracking(const stocs::TrackingCounts& counts);

  /// Every counter as a key-value pair; `queued[i]`: messages of input i waiting in the
  /// synchronizer. Level WARN when frames were rejected or messages dropped since the previous
  /// call, else OK.
  diagnostic_msgs::DiagnosticStatus status(const std::string& name,
                                           const std::vector<size_t>& queued);
  /// One line for the log: frames by outcome and drops by reason.
  std::string summary() const;

 private:
  struct InputCounts {
    std::string topic;
    uint64_t received = 0;
    std::array<uint64_t, kDropReasonCount> dropped{};
  };

  uint64_t droppedTotal() const;  // caller holds mutex_
  uint64_t inProgress() const;    // caller holds mutex_

  mutable std::mutex mutex_;
  std::vector<InputCounts> inputs_;
  uint64_t matched_ = 0, estimated_ = 0, replaced_ = 0, kept_ = 0;
  std::map<std::string, uint64_t> rejected_;  // by kind
  uint64_t rejected_total_ = 0;
  uint64_t service_calls_ = 0, service_failures_ = 0;
  uint64_t time_jumps_ = 0;
  uint64_t poses_published_ = 0, poses_rejected_ = 0;
  uint64_t tracked_ = 0, redetected_ = 0, lost_ = 0, hidden_ = 0, detections_ = 0;
  uint64_t track_resets_ = 0;
  uint64_t reported_problems_ = 0;  // rejected + dropped at the previous status()
};

}  // namespace stocs_ros
