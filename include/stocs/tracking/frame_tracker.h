#pragma once
// Tracking every object of a stream of frames (ObjectTracker per object), with the frames' stamps:
// a gap longer than TrackingParams::max_gap or a stamp going back (a bag played in a loop) ends
// every track first. Shared by `stocs estimate --track` and the ROS node.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "stocs/estimation/frame.h"
#include "stocs/tracking/object_tracker.h"

namespace stocs {

/// One object's outcome of a frame: the estimate holds one instance per track (ObjectTracking).
struct TrackedObject {
  ObjectResult result;
  std::vector<TrackState> states;  ///< per instance of result.estimate
  bool detected = false;           ///< full detection ran for it
};

/// What became of a frame's objects: instances by state, and the objects detected in full.
struct TrackingCounts {
  int tracked = 0;
  int redetected = 0;
  int lost = 0;
  int hidden = 0;      ///< held behind a nearer surface (TrackState::kHidden)
  int detections = 0;  ///< objects that ran full detection
  bool reset = false;  ///< the tracks were ended before the frame (gap or time going back)
};

struct FrameTracking {
  std::vector<TrackedObject> objects;
  TrackingCounts counts;
};

/// Full detections of some objects in one frame, for FrameTracker::follow.
struct FrameDetection {
  std::uint64_t generation = 0;       ///< FrameTracker::generation() of the frame detected
  std::vector<ObjectResult> objects;  ///< estimateFrame's results
};

class FrameTracker {
 public:
  /// Throws InputError naming the first parameter out of range.
  explicit FrameTracker(const TrackingParams& params);

  /// The objects of `frame`, taken at `stamp` (seconds), as estimateFrame takes them (same
  /// errors); each keeps its tracks by name. `previous_input`, where the caller skipped input
  /// frames (a node that keeps up by taking the newest frame), is the stamp of the input frame
  /// before this one: the gap test measures the input's gap, not the time the tracker took. The
  /// objects follow their tracks in parallel (StocsParams::threads, 0: every core), then search and
  /// detect where needed one after the other. Of the objects whose scheduled full detection is
  /// due, the first in `objects` runs it; the others wait for later frames.
  FrameTracking track(const Frame& frame, const std::vector<FrameObject>& objects,
                      const PipelineParams& params, double stamp,
                      std::optional<double> previous_input = std::nullopt);
  /// Tracking without detection in the frame, for a caller that detects in the background
  /// (StreamTracker): first merges `detection` (full detections of an earlier frame; dropped when
  /// the tracks ended since) into the tracks of the objects in `objects` (ObjectTracker::merge),
  /// then follows every track (ObjectTracker::followOnly), objects in parallel. A track followed
  /// from a merged pose is reported redetected and its object detected; a track not accepted is
  /// lost until a detection finds it. Errors as track()'s.
  FrameTracking follow(const Frame& frame, const std::vector<FrameObject>& objects,
                       const PipelineParams& params, double stamp,
                       std::optional<double> previous_input, const FrameDetection* detection);
  /// The objects of `objects` that want full detection after the last frame: each without a track
  /// or with a lost one, and the first whose schedule (TrackingParams::redetect_every) is due.
  std::vector<FrameObject> detectionWanted(const std::vector<FrameObject>& objects) const;
  /// Counts the resets: a detection of an earlier generation belongs to ended tracks.
  std::uint64_t generation() const { return generation_; }

  /// Ends every track: the next frame starts with detection.
  void reset();

  const TrackingParams& params() const { return params_; }
  /// New parameters from the next frame on, every track kept (a node's runtime settings). Throws
  /// InputError naming the first parameter out of range, keeping the old ones.
  void setParams(const TrackingParams& params);
  /// Each object's tracker, by name.
  const std::map<std::string, ObjectTracker>& objects() const { return objects_; }

  /// Whether a frame was tracked since the construction or the last reset.
  bool started() const { return last_stamp_.has_value(); }
  /// Whether a frame at `stamp` (the input's previous frame at `previous_input`, else the last
  /// tracked one) must not continue the tracks.
  bool timeJumped(double stamp, std::optional<double> previous_input) const;

 private:
  /// Ends the tracks if the frame at `stamp` may not continue them (counted in `out`); the time
  /// since the last frame (0 after a reset).
  double begin(FrameTracking& out, double stamp, std::optional<double> previous_input);

  struct Inputs {
    std::vector<ObjectInput> inputs;       // per object
    std::vector<ObjectTracker*> trackers;  // per object, created where new
  };
  /// What each object reads (pointing into the arguments) and its tracker.
  Inputs inputs(const Frame& frame, const CameraIntrinsics& camera,
                const std::vector<FrameObject>& objects, const PipelineParams& params);
  /// The frame-level explanation (explainFrame) over the poses of `out`, the frame's objects in
  /// the order of `objects`: a track whose pose other poses explain is lost.
  void explain(const Frame& frame, const CameraIntrinsics& camera,
               const std::vector<FrameObject>& objects, const PipelineParams& params,
               FrameTracking& out);
  /// The tracks that took a pose of `detection`, by object name.
  std::map<std::string, std::vector<int>> merge(const FrameDetection& detection,
                                                const std::vector<FrameObject>& objects,
                                                const PipelineParams& params);

  TrackingParams params_;
  std::map<std::string, ObjectTracker> objects_;
  std::optional<double> last_stamp_;
  std::uint64_t generation_ = 0;
};

}  // namespace stocs
