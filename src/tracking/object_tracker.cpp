#include "stocs/tracking/object_tracker.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <stdexcept>

#include "stocs/estimation/pipeline.h"
#include "stocs/estimation/pose_proximity.h"
#include "stocs/tracking/segment_follower.h"

namespace stocs {
namespace {

using Clock = std::chrono::steady_clock;

/// The accepted instances of an estimate, best first.
std::vector<InstancePose> acceptedPoses(const PoseEstimate& estimate) {
  std::vector<InstancePose> out;
  for (const InstancePose& p : estimate.instances) {
    if (p.accepted) out.push_back(p);
  }
  return out;
}

}  // namespace

const char* toString(TrackState state) {
  switch (state) {
    case TrackState::kTracked:
      return "tracked";
    case TrackState::kRedetected:
      return "redetected";
    case TrackState::kLost:
      return "lost";
  }
  return "unknown";
}

/// One frame's update of the tracks: which are settled (hold an accepted pose of this frame), and
/// the attempts of those that are not.
class ObjectTracker::Step {
 public:
  Step(ObjectTracker& tracker, const ObjectInput& in, double dt, bool may_redetect)
      : tracker_(tracker),
        in_(in),
        dt_(dt),
        may_redetect_(may_redetect),
        extent_(in.model->model),
        settled_(tracker.tracks_.size(), 0),
        attempts_(tracker.tracks_.size()) {}

  /// Follows the live tracks.
  void follow() {
    const auto start = Clock::now();
    failed_ = followLiveTracks();
    seconds_ = std::chrono::duration<double>(Clock::now() - start).count();
  }

  /// Searches and detects where following failed (or the schedule asks), and reports the frame.
  ObjectTracking conclude() {
    const auto start = Clock::now();
    ObjectTracking out;
    const TrackingParams& params = tracker_.params_;
    const bool scheduled = may_redetect_ && tracker_.redetectionDue();
    ++tracker_.frames_since_detection_;
    std::optional<PoseEstimate> search;  // the last one run: local, then full
    if (failed_ && params.local_search && follower_) {
      search = follower_->search();
      assign(acceptedPoses(*search));
      out.searched = true;
    }
    if (unsettled() || scheduled) {
      search = estimateObject(*in_.cloud, static_cast<float>(in_.camera->fx), *in_.probability,
                              *in_.model, *in_.params, in_.boundary, in_.camera);
      tracker_.frames_since_detection_ = 0;
      assign(acceptedPoses(*search));
      out.detected = true;
    }
    out.estimate = search ? std::move(*search) : PoseEstimate{};
    report(out);
    out.estimate.seconds = seconds_ + std::chrono::duration<double>(Clock::now() - start).count();
    return out;
  }

 private:
  /// Follows every track that is not lost on the segment of their predicted boxes; true when one
  /// of them failed.
  bool followLiveTracks() {
    std::vector<Track>& tracks = tracker_.tracks_;
    std::vector<Eigen::Isometry3f> predicted(tracks.size());
    cv::Rect box;
    for (size_t k = 0; k < tracks.size(); ++k) {
      if (tracks[k].state == TrackState::kLost) continue;
      predicted[k] =
          tracks[k].motion.predict(tracks[k].pose.pose, dt_, tracker_.params_.velocity_damping);
      box |= predictedBox(extent_, predicted[k], *in_.camera, tracker_.params_.roi_margin);
    }
    if (box.empty()) return false;
    follower_.emplace(in_, box);
    bool failed = false;
    for (size_t k = 0; k < tracks.size(); ++k) {
      if (tracks[k].state == TrackState::kLost) continue;
      InstancePose pose = follower_->follow(predicted[k]);
      if (!pose.accepted) {
        attempts_[k] = std::move(pose);
        failed = true;
        continue;
      }
      tracks[k].motion.update(tracks[k].pose.pose, pose.pose, dt_);
      tracks[k].pose = std::move(pose);
      tracks[k].state = TrackState::kTracked;
      settled_[k] = 1;
    }
    return failed;
  }

  bool unsettled() const {
    return tracker_.tracks_.empty() || std::count(settled_.begin(), settled_.end(), 0) > 0;
  }

  /// The track whose pose's model centre is nearest `pose`'s within the match distance, among
  /// those `claimed` leaves free, or -1.
  int nearestTrack(const InstancePose& pose, const std::vector<char>& claimed) const {
    const float reach = tracker_.params_.match_distance * in_.model->model.diameter;
    const Eigen::Vector3f at = pose.pose * extent_.centre();
    int best = -1;
    float best_distance = reach;
    for (size_t k = 0; k < tracker_.tracks_.size(); ++k) {
      const float d = (tracker_.tracks_[k].pose.pose * extent_.centre() - at).norm();
      if (!claimed[k] && d < best_distance) {
        best = static_cast<int>(k);
        best_distance = d;
      }
    }
    return best;
  }

  /// Where an accepted pose that continues no track goes: a track without a pose this frame, a
  /// new track while there is room, or else the settled track it is preferred to (a tracked pose
  /// on a look-alike, whose confidence is lower), or -1.
  int placeFor(const InstancePose& pose, const std::vector<char>& claimed) {
    std::vector<Track>& tracks = tracker_.tracks_;
    for (size_t k = 0; k < tracks.size(); ++k) {
      if (!claimed[k] && !settled_[k]) return static_cast<int>(k);
    }
    if (tracks.size() < static_cast<size_t>(in_.params->stocs.instances)) {
      tracks.push_back({static_cast<int>(tracks.size()), TrackState::kRedetected, pose,
                        ConstantVelocity(extent_.centre())});
      settled_.push_back(0);
      attempts_.emplace_back();
      return static_cast<int>(tracks.size()) - 1;
    }
    int weakest = -1;
    for (size_t k = 0; k < tracks.size(); ++k) {
      if (claimed[k]) continue;
      if (weakest < 0 || tracks[k].pose.confidence < tracks[weakest].pose.confidence) {
        weakest = static_cast<int>(k);
      }
    }
    return weakest >= 0 && tracks[weakest].pose.confidence < pose.confidence ? weakest : -1;
  }

  /// Hands the accepted poses of a search or detection (best first) to the tracks: each continues
  /// its nearest track (a settled one keeps its tracked pose unless the detection's confidence is
  /// higher), the others go where placeFor says.
  void assign(const std::vector<InstancePose>& found) {
    std::vector<char> claimed(tracker_.tracks_.size(), 0);
    std::vector<const InstancePose*> unmatched;
    for (const InstancePose& pose : found) {
      const int k = nearestTrack(pose, claimed);
      if (k < 0) {
        unmatched.push_back(&pose);
        continue;
      }
      claimed[k] = 1;
      // A settled track keeps its tracked pose unless the confidence prefers the detection: the
      // same place turned otherwise (a mug's handle) is no other track, but may be the right pose.
      if (!settled_[k] || pose.confidence > tracker_.tracks_[k].pose.confidence) take(k, pose);
    }
    for (const InstancePose* pose : unmatched) {
      const int k = placeFor(*pose, claimed);
      if (k < 0) continue;
      claimed.resize(tracker_.tracks_.size(), 0);
      claimed[k] = 1;
      take(k, *pose);
    }
  }

  void take(int k, const InstancePose& pose) {
    Track& track = tracker_.tracks_[k];
    track.pose = pose;
    track.state = TrackState::kRedetected;
    track.motion.stop();  // a detection says nothing of the motion
    settled_[k] = 1;
  }

  /// Unsettled tracks become lost; every track's pose of the frame goes into `out`, in index order.
  void report(ObjectTracking& out) {
    PoseEstimate& e = out.estimate;
    e.instances.clear();
    for (size_t k = 0; k < tracker_.tracks_.size(); ++k) {
      Track& track = tracker_.tracks_[k];
      InstancePose pose = track.pose;
      if (!settled_[k]) {
        track.state = TrackState::kLost;
        track.motion.stop();
        if (attempts_[k]) pose.confidence = attempts_[k]->confidence;
        pose.accepted = false;
        pose.rejection = attempts_[k] ? "lost: tracking " + attempts_[k]->rejection +
                                            "; detection found no accepted pose for it"
                                      : "lost: detection found no accepted pose for it";
      }
      e.instances.push_back(std::move(pose));
      out.states.push_back(track.state);
    }
    e.takeFirstInstance();
    if (!out.detected && !out.searched && follower_) {
      e.segment_points = follower_->segment().size();
    }
  }

  ObjectTracker& tracker_;
  const ObjectInput& in_;
  double dt_;
  bool may_redetect_;
  PoseProximity extent_;
  std::vector<char> settled_;
  std::vector<std::optional<InstancePose>> attempts_;  // failed follows, by track
  std::optional<SegmentFollower> follower_;
  bool failed_ = false;  // a live track was not accepted
  double seconds_ = 0;   // of follow()
};

ObjectTracker::ObjectTracker(const TrackingParams& params) : params_(params) {
  params_.validate();
}

ObjectTracker::~ObjectTracker() = default;
ObjectTracker::ObjectTracker(ObjectTracker&&) noexcept = default;
ObjectTracker& ObjectTracker::operator=(ObjectTracker&&) noexcept = default;

ObjectTracking ObjectTracker::update(const ObjectInput& in, double dt, bool may_redetect) {
  follow(in, dt, may_redetect);
  return conclude();
}

void ObjectTracker::follow(const ObjectInput& in, double dt, bool may_redetect) {
  step_ = std::make_unique<Step>(*this, in, dt, may_redetect);
  step_->follow();
}

ObjectTracking ObjectTracker::conclude() {
  if (!step_) throw std::logic_error("ObjectTracker::conclude without follow");
  const std::unique_ptr<Step> step = std::move(step_);
  return step->conclude();
}

bool ObjectTracker::redetectionDue() const {
  return params_.redetect_every > 0 && frames_since_detection_ + 1 >= params_.redetect_every;
}

}  // namespace stocs
