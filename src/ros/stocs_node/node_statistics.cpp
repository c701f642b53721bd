#include "stocs_ros/stocs_node/node_statistics.h"

#include <diagnostic_msgs/KeyValue.h>
#include <fmt/format.h>

#include <numeric>

#include "stocs/util/error.h"

namespace stocs_ros {

std::string rejectionKind(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const stocs::InputError& e) {
    const std::string what = e.what();
    return what.substr(0, what.find(": "));
  } catch (...) {
    return "internal error";
  }
}

NodeStatistics::NodeStatistics(std::vector<std::string> topics) {
  for (std::string& t : topics) inputs_.push_back({std::move(t)});
}

void NodeStatistics::received(size_t input) {
  std::lock_guard<std::mutex> lock(mutex_);
  ++inputs_[input].received;
}

void NodeStatistics::dropped(const std::vector<DroppedMessage>& messages) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const DroppedMessage& m : messages) {
    ++inputs_[m.input].dropped[static_cast<size_t>(m.reason)];
  }
}

void NodeStatistics::matched() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++matched_;
}

void NodeStatistics::kept() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++kept_;
}

void NodeStatistics::replaced() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++replaced_;
}

void NodeStatistics::poses(size_t published, size_t rejected) {
  std::lock_guard<std::mutex> lock(mutex_);
  poses_published_ += published;
  poses_rejected_ += rejected;
}

void NodeStatistics::estimated() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++estimated_;
}

void NodeStatistics::rejected(const std::string& kind) {
  std::lock_guard<std::mutex> lock(mutex_);
  ++rejected_[kind];
  ++rejected_total_;
}

void NodeStatistics::serviceCall(bool success) {
  std::lock_guard<std::mutex> lock(mutex_);
  ++service_calls_;
  if (!success) ++service_failures_;
}

void NodeStatistics::timeJumpedBack() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++time_jumps_;
}

void NodeStatistics::tracking(const stocs::TrackingCounts& counts) {
  std::lock_guard<std::mutex> lock(mutex_);
  tracked_ += static_cast<uint64_t>(counts.tracked);
  redetected_ += static_cast<uint64_t>(counts.redetected);
  lost_ += static_cast<uint64_t>(counts.lost);
  hidden_ += static_cast<uint64_t>(counts.hidden);
  detections_ += static_cast<uint64_t>(counts.detections);
  track_resets_ += counts.reset;
}

uint64_t NodeStatistics::droppedTotal() const {
  uint64_t total = 0;
  for (const InputCounts& in : inputs_) {
    total += std::accumulate(in.dropped.begin(), in.dropped.end(), uint64_t{0});
  }
  return total;
}

uint64_t NodeStatistics::inProgress() const {
  return matched_ - estimated_ - replaced_ - rejected_total_ - kept_;
}

diagnostic_msgs::DiagnosticStatus NodeStatistics::status(const std::string& name,
                                                         const std::vector<size_t>& queued) {
  std::lock_guard<std::mutex> lock(mutex_);
  diagnostic_msgs::DiagnosticStatus out;
  out.name = name;
  const auto add = [&out](std::string key, uint64_t value) {
    diagnostic_msgs::KeyValue kv;
    kv.key = std::move(key);
    kv.value = std::to_string(value);
    out.values.push_back(std::move(kv));
  };
  for (size_t i = 0; i < inputs_.size(); ++i) {
    const InputCounts& in = inputs_[i];
    add("received " + in.topic, in.received);
    for (size_t r = 0; r < kDropReasonCount; ++r) {
      add(fmt::format("dropped {}: {}", in.topic, shortName(static_cast<DropReason>(r))),
          in.dropped[r]);
    }
    add("queued " + in.topic, queued.at(i));
  }
  add("frames matched", matched_);
  add("frames estimated", estimated_);
  add("frames replaced", replaced_);
  add("frames rejected", rejected_total_);
  for (const auto& [kind, count] : rejected_) add("frames rejected: " + kind, count);
  add("frames kept", kept_);
  add("frames in progress", inProgress());
  add("service calls", service_calls_);
  add("service calls failed", service_failures_);
  add("time jumps back", time_jumps_);
  add("poses published", poses_published_);
  add("poses rejected", poses_rejected_);
  add("poses tracked", tracked_);
  add("poses redetected", redetected_);
  add("poses lost", lost_);
  add("poses hidden", hidden_);
  add("full detections while tracking", detections_);
  add("tracking resets", track_resets_);

  const uint64_t problems = rejected_total_ + droppedTotal();
  out.level = problems > reported_problems_ ? diagnostic_msgs::DiagnosticStatus::WARN
                                            : diagnostic_msgs::DiagnosticStatus::OK;
  reported_problems_ = problems;
  out.message = fmt::format("{} frames estimated, {} replaced, {} rejected; {} messages dropped",
                            estimated_, replaced_, rejected_total_, droppedTotal());
  return out;
}

std::string NodeStatistics::summary() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::string line = fmt::format(
      "{} frames matched: {} estimated, {} replaced by a newer frame, {} rejected, {} kept for "
      "~estimate, {} in progress",
      matched_, estimated_, replaced_, rejected_total_, kept_, inProgress());
  for (const auto& [kind, count] : rejected_)
    line += fmt::format("; rejected for {}: {}", kind, count);
  for (const InputCounts& in : inputs_) {
    line += fmt::format("; {}: {} received, dropped {}", in.topic, in.received,
                        describeDropCounts(in.dropped));
  }
  return line + fmt::format(
                    "; {} service calls ({} failed); time went back {} times; {} poses published, "
                    "{} rejected; tracking: {} tracked, {} redetected, {} lost, {} hidden, {} "
                    "full detections, {} resets",
                    service_calls_, service_failures_, time_jumps_, poses_published_,
                    poses_rejected_, tracked_, redetected_, lost_, hidden_, detections_,
                    track_resets_);
}

}  // namespace stocs_ros
