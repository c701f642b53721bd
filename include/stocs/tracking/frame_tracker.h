#pragma once
// Tracking every object of a stream of frames (ObjectTracker per object), with the frames' stamps:
// a gap longer than TrackingParams::max_gap or a stamp going back (a bag played in a loop) ends
// every track first. Shared by `stocs estimate --track` and the ROS node.

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
  int detections = 0;  ///< objects that ran full detection
  bool reset = false;  ///< the tracks were ended before the frame (gap or time going back)
};

struct FrameTracking {
  std::vector<TrackedObject> objects;
  TrackingCounts counts;
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
  /// Ends every track: the next frame starts with detection.
  void reset();

  const TrackingParams& params() const { return params_; }
  /// Each object's tracker, by name.
  const std::map<std::string, ObjectTracker>& objects() const { return objects_; }

 private:
  /// Whether a frame at `stamp` (the input's previous frame at `previous_input`, else the last
  /// tracked one) must not continue the tracks.
  bool timeJumped(double stamp, std::optional<double> previous_input) const;

  TrackingParams params_;
  std::map<std::string, ObjectTracker> objects_;
  std::optional<double> last_stamp_;
};

}  // namespace stocs
