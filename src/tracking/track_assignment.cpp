#include "track_assignment.h"

#include <algorithm>

#include "pose_displacement.h"
#include "stocs/estimation/scheduling/base_consensus.h"

namespace stocs {

TrackAssignment::TrackAssignment(std::vector<Track>& tracks, std::vector<char>& settled,
                                 const TrackingParams& params, const PreparedModel& model,
                                 const PipelineParams& pipeline)
    : tracks_(tracks),
      settled_(settled),
      reach_(params.match_distance * model.model.diameter),
      max_instances_(pipeline.stocs.instances),
      extent_(model.model),
      confidence_(pipeline.confidence),
      model_(model.model),
      symmetries_(model.symmetries),
      separation_(pipeline.stocs.instance_separation * model.model.diameter) {}

const InstanceSeparation& TrackAssignment::samePlace() const {
  if (!same_place_) same_place_.emplace(model_, separation_);
  return *same_place_;
}

float TrackAssignment::challenged(int k) const {
  ConfidenceEvidence evidence = tracks_[k].pose.evidence;
  evidence.consensus =
      std::max(evidence.consensus, consensusShare(tracks_[k].pose.pose, *base_poses_, samePlace(),
                                                  extent_.centre(), separation_));
  return confidence_.confidence(evidence);
}

/// The track whose pose's model centre is nearest `pose`'s within the match distance, among those
/// `claimed` leaves free, or -1.
int TrackAssignment::nearestTrack(const InstancePose& pose,
                                  const std::vector<char>& claimed) const {
  const Eigen::Vector3f at = pose.pose * extent_.centre();
  int best = -1;
  float best_distance = reach_;
  for (size_t k = 0; k < tracks_.size(); ++k) {
    const float d = (tracks_[k].pose.pose * extent_.centre() - at).norm();
    if (!claimed[k] && d < best_distance) {
      best = static_cast<int>(k);
      best_distance = d;
    }
  }
  return best;
}

bool TrackAssignment::turnsHidden(int k, const InstancePose& pose) const {
  const Track& track = tracks_[k];
  if (track.state != TrackState::kHidden) return false;
  const Eigen::Isometry3f& held = track.pose.pose;
  const Eigen::Isometry3f found = nearestEquivalentPose(pose.pose, held, symmetries_);
  return meanDisplacement(model_, found, held) > separation_;
}

/// Where an accepted pose that continues no track goes: a track without a pose this frame, a new
/// track while there is room, or else the track it is preferred to (a tracked pose on a
/// look-alike, or a hidden one, whose confidence is lower), or -1.
int TrackAssignment::placeFor(const InstancePose& pose, const std::vector<char>& claimed) {
  for (size_t k = 0; k < tracks_.size(); ++k) {
    if (!claimed[k] && !settled_[k] && tracks_[k].state != TrackState::kHidden) {
      return static_cast<int>(k);
    }
  }
  if (tracks_.size() < static_cast<size_t>(max_instances_)) {
    tracks_.push_back({static_cast<int>(tracks_.size()), TrackState::kRedetected, pose,
                       ConstantVelocity(extent_.centre())});
    settled_.push_back(0);
    moved_ = true;
    return static_cast<int>(tracks_.size()) - 1;
  }
  int weakest = -1;
  for (size_t k = 0; k < tracks_.size(); ++k) {
    if (claimed[k]) continue;
    if (weakest < 0 || tracks_[k].pose.confidence < tracks_[weakest].pose.confidence) {
      weakest = static_cast<int>(k);
    }
  }
  return weakest >= 0 && challenged(weakest) < pose.confidence ? weakest : -1;
}

std::vector<int> TrackAssignment::assign(const PoseEstimate& found) {
  base_poses_ = &found.base_poses;
  std::vector<int> taken;
  std::vector<char> claimed(tracks_.size(), 0);
  std::vector<const InstancePose*> unmatched;
  for (const InstancePose& pose : found.instances) {
    if (!pose.accepted) continue;
    const int k = nearestTrack(pose, claimed);
    if (k < 0) {
      unmatched.push_back(&pose);
      continue;
    }
    claimed[k] = 1;
    // A settled track keeps its tracked pose unless the confidence prefers the detection: the
    // same place turned otherwise (a mug's handle) is no other track, but may be the right pose.
    // So does a hidden track against a pose that turns or moves it: its visible part alone fits.
    const bool held = settled_[k] || turnsHidden(k, pose);
    if (!held || pose.confidence > challenged(k)) {
      take(k, pose);
      taken.push_back(k);
    }
  }
  for (const InstancePose* pose : unmatched) {
    const int k = placeFor(*pose, claimed);
    if (k < 0) continue;
    claimed.resize(tracks_.size(), 0);
    claimed[k] = 1;
    take(k, *pose);
    taken.push_back(k);
  }
  return taken;
}

InstancePose TrackAssignment::keepingTurn(const InstancePose& pose,
                                          const Eigen::Isometry3f& previous) const {
  InstancePose out = pose;
  out.pose = nearestEquivalentPose(pose.pose, previous, symmetries_);
  float nearest = meanDisplacement(model_, out.pose, previous);
  const ShapeAlternative* kept = nullptr;
  for (const ShapeAlternative& a : pose.ambiguous) {
    const Eigen::Isometry3f turned =
        nearestEquivalentPose(pose.pose * a.motion, previous, symmetries_);
    const float d = meanDisplacement(model_, turned, previous);
    if (d < nearest) {
      nearest = d;
      out.pose = turned;
      kept = &a;
    }
  }
  if (kept) {
    // The alternatives again as motions from the pose taken (a declared symmetry included): the
    // detection's own pose among them.
    const Eigen::Isometry3f back = out.pose.inverse() * pose.pose;
    out.ambiguous = {shapeAlternative(back, kept->shift)};
    for (const ShapeAlternative& a : pose.ambiguous) {
      if (&a != kept) out.ambiguous.push_back(shapeAlternative(back * a.motion, a.shift));
    }
  }
  return out;
}

void TrackAssignment::take(int k, const InstancePose& pose) {
  Track& track = tracks_[k];
  moved_ = moved_ || !samePlace().samePlace(track.pose.pose, pose.pose);
  track.pose = keepingTurn(pose, track.pose.pose);
  track.state = TrackState::kRedetected;
  track.motion.stop();  // a detection says nothing of the motion
  settled_[k] = 1;
}

}  // namespace stocs
