#pragma once
// Tracking of one object's instances from frame to frame (issue 30). Each track keeps the last
// accepted pose, a damped constant velocity and a stable instance index. Per frame:
//   1. every live track is predicted and refined on the segment of its predicted box
//      (SegmentFollower) and judged by the calibrated confidence: accepted -> tracked;
//   2. a track that failed is searched for in the box with StoCS first (local search), then with
//      full detection (detectObject); an accepted pose there -> redetected, else -> lost, or
//      hidden where a nearer surface hides its predicted pose (held at its last pose, which a
//      detection that turns or moves it replaces only where the confidence prefers it: a visible
//      part fits many poses);
//   3. full detection also runs when there is no track, while a track is lost (detection keeps
//      trying), and every TrackingParams::redetect_every frames, so that a track that slid onto a
//      look-alike is replaced by a detection the confidence prefers (FrameTracker lets one object
//      a frame do so, so that the objects' schedules do not all fall on one frame).
// Detected poses continue the track whose model centre is nearest (TrackingParams::
// match_distance), so an instance keeps its index while it is seen; further accepted poses start
// new tracks up to StocsParams::instances.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "stocs/estimation/frame.h"
#include "stocs/tracking/motion_model.h"
#include "stocs/tracking/tracking_params.h"

namespace stocs {

enum class TrackState {
  kTracked,     ///< followed from its predicted pose, and accepted
  kRedetected,  ///< found again (or for the first time) by StoCS, and accepted
  kLost,        ///< no accepted pose this frame: not published; detection keeps trying
  /// Its follow failed only because a nearer surface hides it (TrackingParams::hold_hidden): not
  /// published; held at its last accepted pose and followed from there; a detection that turns
  /// or moves it replaces it only where the confidence prefers it, as it does a tracked pose.
  kHidden,
  kUntracked,  ///< no track: the best pose of the object's last detection, which rejected it
};

/// "tracked", "redetected", "lost", "hidden", "untracked".
const char* toString(TrackState state);

struct Track {
  int index = 0;  ///< stable instance index: TF <object>_<index> for index > 0
  TrackState state = TrackState::kRedetected;
  InstancePose pose;  ///< the last accepted pose
  ConstantVelocity motion;
};

/// One object's outcome of one frame.
struct ObjectTracking {
  /// One instance per track in index order (instance k is track k): accepted unless lost (a lost
  /// instance holds the last accepted pose, rejected with the reason). An object without tracks
  /// has instead its last full detection's best pose, rejected (kUntracked), so that a stream's
  /// every frame says why an absent object has no pose. The counters and stage
  /// times of the last search that ran (full detection, else the local search), else the segment
  /// size of the followed box; `seconds` is the whole step.
  PoseEstimate estimate;
  std::vector<TrackState> states;  ///< per instance
  bool searched = false;           ///< the local search ran
  bool detected = false;           ///< full detection ran
};

class ObjectTracker {
 public:
  /// Throws InputError naming the first parameter out of range.
  explicit ObjectTracker(const TrackingParams& params);
  ~ObjectTracker();
  ObjectTracker(ObjectTracker&&) noexcept;
  ObjectTracker& operator=(ObjectTracker&&) noexcept;
  /// New parameters from the next frame on, the tracks kept; `params` must be valid.
  void setParams(const TrackingParams& params) { params_ = params; }

  /// The object in a new frame `dt` seconds after the previous one: follow(), then conclude(). The
  /// scheduled full detection runs only where `may_redetect` allows it (else on a later frame).
  ObjectTracking update(const ObjectInput& in, double dt, bool may_redetect = true);
  /// The first half of update(): follows the live tracks (one thread; trackers of different
  /// objects may follow at the same time). `in` must outlive the conclude() that follows.
  void follow(const ObjectInput& in, double dt, bool may_redetect = true);
  /// The second half: searches and detects where following failed or the schedule asks (every
  /// thread), and returns the frame's outcome. Only after follow().
  ObjectTracking conclude();
  /// Whether the schedule (TrackingParams::redetect_every) asks for full detection in the next
  /// frame, or the last detection, having started or moved a track, is to be confirmed there.
  bool redetectionDue() const;

  /// For a caller that detects in the background (StreamTracker): follows the live tracks and
  /// reports the frame without searching or detecting; a track that is not accepted is lost until
  /// a detection merged with merge() finds it again.
  ObjectTracking followOnly(const ObjectInput& in, double dt);
  /// Whether an instance is missing: no track yet, or a lost or hidden one (detection keeps
  /// trying).
  bool untracked() const;
  /// Hands the accepted poses of a full detection (of this or an earlier frame) to the tracks as
  /// a frame's detection does, the tracks neither lost nor hidden counting as settled (a detection
  /// the confidence prefers replaces one), and restarts the schedule; the indices of the tracks
  /// that took a pose.
  std::vector<int> merge(const PoseEstimate& detection, const PreparedModel& model,
                         const PipelineParams& params);

  /// Marks track `index` lost after the frame (its pose, accepted alone, was rejected by the
  /// frame-level explanation): it is no longer followed, and detection keeps trying.
  void lose(size_t index);

  const std::vector<Track>& tracks() const { return tracks_; }

 private:
  class Step;
  TrackingParams params_;
  std::vector<Track> tracks_;  // by index: indices are 0, 1, ... in order of first detection
  int frames_since_detection_ = 0;
  /// The last detection started a track or moved one: the next frame detects again, as a single
  /// detection may land on a look-alike that following would then keep.
  bool confirm_detection_ = false;
  /// The best pose of the last full detection when it was rejected (reported while no track).
  std::optional<InstancePose> unfound_;
  /// A full detection ran: restarts the schedule, clears the confirmation it answers, and keeps
  /// `detection`'s best pose in unfound_ when rejected.
  void detectionRan(const PoseEstimate& detection);
  std::unique_ptr<Step> step_;  // between follow() and conclude()
};

}  // namespace stocs
