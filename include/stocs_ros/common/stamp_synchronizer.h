#pragma once
// Matches messages of N inputs by header stamp: one frame is the newest message of input 0 (the
// reference, the cloud) together with, for every other input, the message nearest to its stamp
// within a tolerance.
//
// Time going back (a bag played in a loop, a restarted camera driver or simulator) shows as a
// reference stamp at or before the last matched frame's, as one camera's stamps never go back
// otherwise: the synchronizer then starts again on the new timeline, keeping the messages that can
// belong to its first frame. A message of another input stamped at or before the last matched frame
// is held for that reason, until a second frame matched after it shows that it was late (the first
// may be the old timeline's last frame, its cloud still on the way when the new timeline began).
//
// Written here rather than taken from message_filters because its synchronizers are templates
// over at most 9 fixed message types, while the node has one probability input per configured
// object (any number), and because every message dropped here must be counted by reason for the
// node's throttled warnings. Not thread-safe: the caller serialises add().

#include <ros/time.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "stocs/util/param_set.h"

namespace stocs_ros {

struct SyncParams {
  double tolerance = 0.01;  ///< seconds between the reference stamp and the stamps it is matched to
  int queue_size = 10;      ///< messages kept per input while waiting for a match
  /// Seconds behind the newest stamp seen before a message is dropped; 0: never.
  double max_age = 2.0;

  static const stocs::ParamSet<SyncParams>& schema();
  /// Throws stocs::InputError naming the first value out of range.
  void validate() const;
};

enum class DropReason {
  kQueueFull,  ///< the input's queue overflowed; its oldest message went
  kUnmatched,  ///< a newer frame was matched first
  kLate,       ///< stamped at or before the frame matched before it arrived
  kTooOld,     ///< older than max_age behind the newest stamp seen
  kTimeJump,   ///< waiting for a frame of the timeline that time went back from
};
constexpr size_t kDropReasonCount = 5;

const char* toString(DropReason reason);
/// Two words or fewer: "queue full", "unmatched", "late", "too old", "time jump".
const char* shortName(DropReason reason);

struct DroppedMessage {
  size_t input;
  ros::Time stamp;
  DropReason reason;
};

/// Drop counts by reason, as "2 queue full, 1 late" (reasons with zero counts left out).
std::string describeDropCounts(const std::array<uint64_t, kDropReasonCount>& counts);

template <class Message>
class StampSynchronizer {
 public:
  struct Match {
    ros::Time stamp;                ///< the reference message's stamp
    std::vector<Message> messages;  ///< one per input, in input order
  };

  StampSynchronizer(size_t inputs, const SyncParams& params)
      : params_(params), queues_(inputs), held_(inputs) {}

  /// Adds a message of `input` and returns a complete frame when one can now be formed. Messages
  /// dropped on the way are appended to `dropped` and counted.
  std::optional<Match> add(size_t input, const ros::Time& stamp, Message message,
                           std::vector<DroppedMessage>& dropped) {
    if (last_match_ && stamp <= *last_match_) {
      if (input > 0) {
        // Late, or the first of a new timeline: the reference input's next stamp tells.
        hold(input, Entry{stamp, std::move(message)}, dropped);
        return std::nullopt;
      }
      restartTime(stamp, dropped);
    }
    if (!newest_ || stamp > *newest_) newest_ = stamp;
    // ros::Time cannot be negative: no age limit applies in the first max_age seconds of a clock.
    if (params_.max_age > 0 && newest_->toSec() > params_.max_age) {
      const ros::Time limit = *newest_ - ros::Duration(params_.max_age);
      dropOlderThan(limit, dropped);
      if (stamp < limit) {
        drop(input, stamp, DropReason::kTooOld, dropped);
        return std::nullopt;
      }
    }
    enqueue(input, Entry{stamp, std::move(message)}, dropped);
    return tryMatch(dropped);
  }

  const std::array<uint64_t, kDropReasonCount>& dropCounts() const { return counts_; }
  /// How often time went back (see the top of this file).
  uint64_t timeJumps() const { return time_jumps_; }
  /// Messages of `input` waiting for a match.
  size_t queued(size_t input) const { return queues_[input].size() + held_[input].size(); }
  size_t inputs() const { return queues_.size(); }

 private:
  struct Entry {
    ros::Time stamp;
    Message message;
  };
  struct Held {
    Entry entry;
    uint64_t matches_before;  ///< frames matched before it came
  };

  void drop(size_t input, const ros::Time& stamp, DropReason reason,
            std::vector<DroppedMessage>& dropped) {
    ++counts_[static_cast<size_t>(reason)];
    dropped.push_back({input, stamp, reason});
  }

  /// Inserts in stamp order; a full queue loses its oldest message.
  void enqueue(size_t input, Entry entry, std::vector<DroppedMessage>& dropped) {
    std::deque<Entry>& queue = queues_[input];
    const auto at =
        std::upper_bound(queue.begin(), queue.end(), entry.stamp,
                         [](const ros::Time& s, const Entry& e) { return s < e.stamp; });
    queue.insert(at, std::move(entry));
    if (static_cast<int>(queue.size()) > params_.queue_size) {
      drop(input, queue.front().stamp, DropReason::kQueueFull, dropped);
      queue.pop_front();
    }
  }

  /// Keeps a message stamped at or before the last matched frame until time goes back (it is part
  /// of the new timeline's first frame) or two more frames are matched (it was late).
  void hold(size_t input, Entry entry, std::vector<DroppedMessage>& dropped) {
    std::deque<Held>& held = held_[input];
    held.push_back({std::move(entry), matches_});
    if (static_cast<int>(held.size()) > params_.queue_size) {
      drop(input, held.front().entry.stamp, DropReason::kLate, dropped);
      held.pop_front();
    }
  }

  void dropOlderThan(const ros::Time& limit, std::vector<DroppedMessage>& dropped) {
    for (size_t i = 0; i < queues_.size(); ++i) {
      while (!queues_[i].empty() && queues_[i].front().stamp < limit) {
        drop(i, queues_[i].front().stamp, DropReason::kTooOld, dropped);
        queues_[i].pop_front();
      }
    }
  }

  /// Starts again on the timeline of a reference stamped `stamp`: forgets the last matched frame,
  /// keeps the messages that can be matched to it or to an earlier reference (held ones included),
  /// and drops those stamped after it, which waited for the old timeline's next frames.
  void restartTime(const ros::Time& stamp, std::vector<DroppedMessage>& dropped) {
    ++time_jumps_;
    last_match_.reset();
    newest_.reset();
    const ros::Time latest = stamp + ros::Duration(params_.tolerance);
    for (size_t i = 0; i < queues_.size(); ++i) {
      std::deque<Entry>& queue = queues_[i];
      while (!queue.empty() && queue.back().stamp > latest) {
        drop(i, queue.back().stamp, DropReason::kTimeJump, dropped);
        queue.pop_back();
      }
      for (Held& h : held_[i]) {
        if (h.entry.stamp > latest) {
          drop(i, h.entry.stamp, DropReason::kTimeJump, dropped);
        } else {
          enqueue(i, std::move(h.entry), dropped);
        }
      }
      held_[i].clear();
      if (!queue.empty() && (!newest_ || queue.back().stamp > *newest_)) {
        newest_ = queue.back().stamp;
      }
    }
  }

  /// Index of the message of `input` nearest to `stamp` within the tolerance, or -1.
  int nearest(size_t input, const ros::Time& stamp) const {
    int best = -1;
    double best_gap = params_.tolerance;
    const std::deque<Entry>& queue = queues_[input];
    for (size_t k = 0; k < queue.size(); ++k) {
      const double gap = std::abs((queue[k].stamp - stamp).toSec());
      if (gap <= best_gap) {
        best = static_cast<int>(k);
        best_gap = gap;
      }
    }
    return best;
  }

  std::optional<Match> tryMatch(std::vector<DroppedMessage>& dropped) {
    const std::deque<Entry>& references = queues_[0];
    std::vector<int> chosen(queues_.size());
    // Newest reference first: a live consumer wants the latest complete frame.
    for (int r = static_cast<int>(references.size()) - 1; r >= 0; --r) {
      chosen[0] = r;
      bool complete = true;
      for (size_t i = 1; i < queues_.size() && complete; ++i) {
        chosen[i] = nearest(i, references[r].stamp);
        complete = chosen[i] >= 0;
      }
      if (complete) return take(chosen, dropped);
    }
    return std::nullopt;
  }

  /// Moves the chosen messages out and drops every message older than them, and the messages held
  /// since before the previous match: time did not go back, so they were late.
  Match take(const std::vector<int>& chosen, std::vector<DroppedMessage>& dropped) {
    Match match;
    match.stamp = queues_[0][chosen[0]].stamp;
    for (size_t i = 0; i < queues_.size(); ++i) {
      std::deque<Held>& held = held_[i];
      while (!held.empty() && held.front().matches_before < matches_) {
        drop(i, held.front().entry.stamp, DropReason::kLate, dropped);
        held.pop_front();
      }
      std::deque<Entry>& queue = queues_[i];
      for (int k = 0; k < chosen[i]; ++k) drop(i, queue[k].stamp, DropReason::kUnmatched, dropped);
      match.messages.push_back(std::move(queue[chosen[i]].message));
      queue.erase(queue.begin(), queue.begin() + chosen[i] + 1);
    }
    last_match_ = match.stamp;
    ++matches_;
    return match;
  }

  SyncParams params_;
  std::vector<std::deque<Entry>> queues_;  // each sorted by stamp, oldest first
  std::vector<std::deque<Held>> held_;     // stamped at or before last_match_, in arrival order
  std::optional<ros::Time> newest_;
  std::optional<ros::Time> last_match_;
  std::array<uint64_t, kDropReasonCount> counts_{};
  uint64_t time_jumps_ = 0;
  uint64_t matches_ = 0;
};

}  // namespace stocs_ros
