#pragma once
// Hands the accepted poses of a search or a detection to an object's tracks (ObjectTracker): each
// pose continues its nearest track (TrackingParams::match_distance); a settled track (one holding
// an accepted pose of this frame) keeps it unless the confidence prefers the detection; the other
// poses go to a track without a pose, a new track while there is room (StocsParams::instances), or
// replace the settled track with the lowest confidence when they have a higher one. A settled
// pose is compared with its consensus among the detection's bases: a followed pose has no bases of
// its own, and its zero consensus would let any detection win. A hidden track (TrackState::kHidden)
// is continued by a pose within the instance separation of its held pose by ADD (up to declared
// symmetries), and holds it as a settled track does against one that turns or moves it: the
// visible part of a hidden object fits other poses.

#include <optional>
#include <vector>

#include "stocs/estimation/instance_separation.h"
#include "stocs/estimation/pipeline.h"
#include "stocs/estimation/pose_proximity.h"
#include "stocs/tracking/object_tracker.h"

namespace stocs {

class TrackAssignment {
 public:
  /// `settled`: per track, whether it holds an accepted pose of this frame; grows with the tracks
  /// and marks those the assignment takes. Both vectors must outlive the assignment.
  TrackAssignment(std::vector<Track>& tracks, std::vector<char>& settled,
                  const TrackingParams& params, const PreparedModel& model,
                  const PipelineParams& pipeline);

  /// Hands out the accepted poses of `found` (best first); the indices of the tracks that took
  /// one.
  std::vector<int> assign(const PoseEstimate& found);
  /// Whether a pose assigned so far started a track or moved one to another place (up to
  /// symmetries): a single detection there is to be confirmed by the next.
  bool moved() const { return moved_; }

 private:
  int nearestTrack(const InstancePose& pose, const std::vector<char>& claimed) const;
  int placeFor(const InstancePose& pose, const std::vector<char>& claimed);
  void take(int k, const InstancePose& pose);
  /// Whether track k is hidden and `pose`, up to declared symmetries, moves its held pose's model
  /// points by more than the instance separation on average (ADD).
  bool turnsHidden(int k, const InstancePose& pose) const;
  /// `pose` as the track at `previous` takes it: of the pose and the turns it names as fitting as
  /// well (InstancePose::ambiguous), each up to declared symmetries, the one nearest `previous`
  /// (ADD), with the turns named from it. Where the data cannot tell turns apart, the track keeps
  /// its own instead of alternating with each detection.
  InstancePose keepingTurn(const InstancePose& pose, const Eigen::Isometry3f& previous) const;
  /// Track k's confidence with its consensus among the bases of the poses being assigned.
  float challenged(int k) const;
  /// The model's same-place test, built on first use: a search or detection that found no
  /// accepted pose (an absent object) needs none.
  const InstanceSeparation& samePlace() const;

  std::vector<Track>& tracks_;
  std::vector<char>& settled_;
  float reach_;  // the match distance in metres
  int max_instances_;
  PoseProximity extent_;
  const ConfidenceParams& confidence_;
  const ObjectModel& model_;
  const ObjectSymmetries& symmetries_;  ///< declared: a detection takes the track's equivalent
  float separation_;                    // of instances, in metres
  mutable std::optional<InstanceSeparation> same_place_;        // samePlace()
  const std::vector<Eigen::Isometry3f>* base_poses_ = nullptr;  // of the poses being assigned
  bool moved_ = false;
};

}  // namespace stocs
