#pragma once
// Tracking a live stream (the ROS node) with full detection off the frame's critical path: every
// frame is only followed (FrameTracker::follow), at tracking cost, while full detection (objects
// without a track, lost ones, and the one whose schedule is due) runs on one background thread on
// the latest frame it can take, and its result is merged into the tracks at the first frame after
// it finished. `stocs estimate --track` keeps FrameTracker::track, which detects within the frame
// and is deterministic.

#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "stocs/tracking/frame_tracker.h"

namespace stocs {

class StreamTracker {
 public:
  /// Throws InputError naming the first parameter out of range.
  explicit StreamTracker(const TrackingParams& params);
  /// Waits for a running detection to finish.
  ~StreamTracker();
  StreamTracker(const StreamTracker&) = delete;
  StreamTracker& operator=(const StreamTracker&) = delete;

  /// Follows the objects of `frame` as FrameTracker::follow does (same errors), merging the last
  /// detection that finished; then, when no detection runs and one is wanted, starts it on
  /// `frame` with one thread fewer than the tracking uses (the other follows the next frames).
  /// `keep` is held until that detection ends (what the objects' models belong to). The first
  /// frame, and a frame that ends the tracks (FrameTracker::timeJumped: a gap or time going back),
  /// are instead detected in place, as FrameTracker::track does.
  FrameTracking track(std::shared_ptr<const Frame> frame, const std::vector<FrameObject>& objects,
                      const PipelineParams& params, double stamp,
                      std::optional<double> previous_input = std::nullopt,
                      std::shared_ptr<const void> keep = nullptr);
  /// Waits until no detection runs (tests; the next track() merges the result).
  void waitForDetection();
  /// The message of the last detection that threw since the last call, if any (its objects stay
  /// as they were; detection is tried again).
  std::optional<std::string> takeDetectionError();

  const FrameTracker& frames() const { return tracker_; }
  /// New parameters from the next frame on, every track kept (FrameTracker::setParams).
  void setParams(const TrackingParams& params) { tracker_.setParams(params); }

 private:
  struct Job {
    std::shared_ptr<const Frame> frame;
    std::vector<FrameObject> objects;
    PipelineParams params;
    std::uint64_t generation = 0;
    std::shared_ptr<const void> keep;
  };

  void run();
  /// Starts detection on the frame when none runs and an object wants one. Under mutex_.
  void startDetection(const std::shared_ptr<const Frame>& frame,
                      const std::vector<FrameObject>& objects, const PipelineParams& params,
                      std::shared_ptr<const void> keep);

  FrameTracker tracker_;  // the caller's thread only
  std::mutex mutex_;
  std::condition_variable wake_, idle_;
  std::optional<Job> job_;              // waiting for the thread
  bool running_ = false;                // a job is waiting or running
  std::optional<FrameDetection> done_;  // finished, not merged yet
  std::optional<std::string> error_;    // of a detection that threw
  bool stopping_ = false;
  std::thread thread_;  // last: starts after every other member is ready
};

}  // namespace stocs
