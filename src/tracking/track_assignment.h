#pragma once
// Hands the accepted poses of a search or a detection to an object's tracks (ObjectTracker): each
// pose continues its nearest track (TrackingParams::match_distance); a settled track (one holding
// an accepted pose of this frame) keeps it unless the confidence prefers the detection; the other
// poses go to a track without a pose, a new track while there is room (StocsParams::instances), or
// replace the settled track with the lowest confidence when they have a higher one.

#include <vector>

#include "stocs/estimation/pose_proximity.h"
#include "stocs/tracking/object_tracker.h"

namespace stocs {

class TrackAssignment {
 public:
  /// `settled`: per track, whether it holds an accepted pose of this frame; grows with the tracks
  /// and marks those the assignment takes. Both vectors must outlive the assignment.
  TrackAssignment(std::vector<Track>& tracks, std::vector<char>& settled,
                  const TrackingParams& params, const PreparedModel& model, int max_instances);

  /// Hands out `found` (accepted poses, best first); the indices of the tracks that took one.
  std::vector<int> assign(const std::vector<InstancePose>& found);

 private:
  int nearestTrack(const InstancePose& pose, const std::vector<char>& claimed) const;
  int placeFor(const InstancePose& pose, const std::vector<char>& claimed);
  void take(int k, const InstancePose& pose);

  std::vector<Track>& tracks_;
  std::vector<char>& settled_;
  float reach_;  // the match distance in metres
  int max_instances_;
  PoseProximity extent_;
};

}  // namespace stocs
