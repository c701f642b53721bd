#pragma once
// Parameters of tracking objects from frame to frame (ObjectTracker, FrameTracker): how a pose is
// predicted, where the next frame is segmented, and when full detection runs again.

#include "stocs/util/param_set.h"

namespace stocs {

struct TrackingParams {
  /// Track instead of detecting every object in every frame. Off here and in `stocs estimate`
  /// (`--track`), whose images are views rather than a stream; the node's default is on.
  bool enabled = false;
  /// Full detection (StoCS on the whole image) also runs every this many frames while an object is
  /// tracked, so that a track that slid onto a look-alike is caught; 0: only when tracking fails.
  int redetect_every = 15;
  /// Seconds: a longer gap between two input frames (or a stamp going back) ends every track, as
  /// the objects may have moved anywhere meanwhile. Frames a node skips while it is busy are no
  /// gap (FrameTracker::track).
  double max_gap = 0.5;
  /// Share of the last velocity the prediction applies (a damped constant velocity); 0 predicts
  /// the last pose.
  float velocity_damping = 0.7f;
  /// A tracked object is segmented in the image box of its predicted bounding sphere, widened by
  /// this share of the box's size on each side.
  float roi_margin = 0.5f;
  /// When tracking fails, StoCS first searches the tracked object's box before the whole image
  /// (FrameTracker::track; StreamTracker, the node's, detects the whole image in the background).
  bool local_search = true;
  /// A detected pose continues a track when its model centre lies within this share of the
  /// object's diameter of the track's (the track keeps its instance index).
  float match_distance = 0.3f;
  /// A track whose follow fails only because a nearer surface hides it (an arm or another object
  /// passing in front; SegmentFollower::hiddenBehindNearerSurface) is held rather than lost: not
  /// published, followed on, and taken by a detection that turns or moves it only where the
  /// confidence prefers that (its visible part alone fits other poses); a follow that moves it past
  /// the instance separation is not taken.
  bool hold_hidden = true;

  /// The defaults with `enabled` on: what a stream of frames (the node) starts from.
  static TrackingParams forStream() {
    TrackingParams p;
    p.enabled = true;
    return p;
  }

  /// Key, range, unit and meaning of every field (docs/parameters.md).
  static const ParamSet<TrackingParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
};

}  // namespace stocs
