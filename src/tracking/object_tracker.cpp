#include "stocs/tracking/object_tracker.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <stdexcept>

#include "pose_displacement.h"
#include "stocs/estimation/pipeline.h"
#include "stocs/estimation/pose_proximity.h"
#include "stocs/tracking/segment_follower.h"
#include "track_assignment.h"

namespace stocs {
namespace {

using Clock = std::chrono::steady_clock;

/// Lost or hidden: the track holds no pose accepted in its last frame.
bool withoutPose(const Track& t) {
  return t.state == TrackState::kLost || t.state == TrackState::kHidden;
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
    case TrackState::kHidden:
      return "hidden";
    case TrackState::kUntracked:
      return "untracked";
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

  /// Searches and detects where following failed (or the schedule asks), unless `detect` is false
  /// (a caller that detects in the background: ObjectTracker::merge), and reports the frame.
  ObjectTracking conclude(bool detect) {
    const auto start = Clock::now();
    ObjectTracking out;
    const TrackingParams& params = tracker_.params_;
    const bool scheduled = may_redetect_ && tracker_.redetectionDue();
    ++tracker_.frames_since_detection_;
    std::optional<PoseEstimate> search;  // the last one run: local, then full
    bool moved = false;                  // a search or detection started a track or moved one
    if (detect && failed_ && params.local_search && follower_) {
      search = follower_->search();
      moved = assign(*search);
      out.searched = true;
    }
    if (detect && (unsettled() || scheduled)) {
      // This object alone, when its own tracks need it: the frame tracker steps its objects in
      // parallel, each on its own schedule, so the frame's entry point does not fit here.
      search = detectObject(in_);
      tracker_.detectionRan(*search);
      moved = assign(*search) || moved;
      out.detected = true;
    }
    if (moved) tracker_.confirm_detection_ = true;
    out.estimate = search ? std::move(*search) : PoseEstimate{};
    report(out, detect);
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
      // About a symmetry the data leaves the pose free: it keeps the predicted equivalent.
      pose.pose = nearestEquivalentPose(pose.pose, predicted[k], in_.model->symmetries);
      const bool hidden = holdsHidden(pose, predicted[k]);
      if (!pose.accepted) {
        // Where predicted, hidden and not contradicted: held at its last pose; else lost until a
        // search or detection finds it.
        tracks[k].state = hidden ? TrackState::kHidden : TrackState::kLost;
        tracks[k].motion.stop();
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

  /// Whether the track predicted at `predicted` is to be held hidden (TrackingParams::hold_hidden):
  /// its follow was not accepted, or it was but moved the pose past the instance separation (ADD),
  /// which the few points left in view of a hidden object do, pulling it anywhere; such a follow
  /// is then rejected.
  bool holdsHidden(InstancePose& follow, const Eigen::Isometry3f& predicted) const {
    if (!tracker_.params_.hold_hidden) return false;
    const ObjectModel& model = in_.model->model;
    const float moved = follow.accepted ? meanDisplacement(model, follow.pose, predicted) : 0;
    const float separation = in_.params->stocs.instance_separation * model.diameter;
    if (follow.accepted && moved <= separation) return false;
    if (!follower_->hiddenBehindNearerSurface(predicted)) return false;
    if (follow.accepted) {
      follow.accepted = false;
      follow.rejection = fmt::format("the few points in view moved it by {:.0f}% of its diameter",
                                     100 * moved / model.diameter);
    }
    return true;
  }

  bool unsettled() const {
    return tracker_.tracks_.empty() || std::count(settled_.begin(), settled_.end(), 0) > 0;
  }

  /// Hands the accepted poses of a search or detection (best first) to the tracks; whether one
  /// started a track or moved one (TrackAssignment::moved).
  bool assign(const PoseEstimate& found) {
    TrackAssignment assignment(tracker_.tracks_, settled_, tracker_.params_, *in_.model,
                               *in_.params);
    assignment.assign(found);
    attempts_.resize(tracker_.tracks_.size());
    return assignment.moved();
  }

  /// Unsettled tracks become lost; every track's pose of the frame goes into `out`, in index order.
  /// `detected_here`: detection could run in this call (else it runs in the background).
  void report(ObjectTracking& out, bool detected_here) {
    const std::string detection = detected_here
                                      ? "detection found no accepted pose for it"
                                      : "detection in the background has not found it again yet";
    PoseEstimate& e = out.estimate;
    e.instances.clear();
    for (size_t k = 0; k < tracker_.tracks_.size(); ++k) {
      Track& track = tracker_.tracks_[k];
      InstancePose pose = track.pose;
      if (!settled_[k] && track.state == TrackState::kHidden && attempts_[k]) {
        pose.confidence = attempts_[k]->confidence;
        pose.accepted = false;
        pose.rejection = "hidden behind a nearer surface, held: " + attempts_[k]->rejection;
      } else if (!settled_[k]) {
        track.state = TrackState::kLost;
        track.motion.stop();
        if (attempts_[k]) pose.confidence = attempts_[k]->confidence;
        pose.accepted = false;
        pose.rejection = attempts_[k]
                             ? "lost: tracking " + attempts_[k]->rejection + "; " + detection
                             : "lost: " + detection;
      }
      e.instances.push_back(std::move(pose));
      out.states.push_back(track.state);
    }
    if (tracker_.tracks_.empty() && tracker_.unfound_) {
      InstancePose pose = *tracker_.unfound_;
      pose.rejection = "not tracked: the last detection's best pose: " + pose.rejection;
      e.instances.push_back(std::move(pose));
      out.states.push_back(TrackState::kUntracked);
    }
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
  return step->conclude(true);
}

ObjectTracking ObjectTracker::followOnly(const ObjectInput& in, double dt) {
  follow(in, dt, false);
  const std::unique_ptr<Step> step = std::move(step_);
  return step->conclude(false);
}

bool ObjectTracker::untracked() const {
  return tracks_.empty() || std::any_of(tracks_.begin(), tracks_.end(), withoutPose);
}

std::vector<int> ObjectTracker::merge(const PoseEstimate& detection, const PreparedModel& model,
                                      const PipelineParams& params) {
  detectionRan(detection);
  std::vector<char> settled;
  for (const Track& t : tracks_) settled.push_back(!withoutPose(t));
  TrackAssignment assignment(tracks_, settled, params_, model, params);
  std::vector<int> taken = assignment.assign(detection);
  confirm_detection_ = assignment.moved();
  return taken;
}

void ObjectTracker::lose(size_t index) {
  Track& track = tracks_.at(index);
  track.state = TrackState::kLost;
  track.motion.stop();
}

void ObjectTracker::detectionRan(const PoseEstimate& detection) {
  frames_since_detection_ = 0;
  confirm_detection_ = false;
  unfound_.reset();
  if (!detection.instances.empty() && !detection.instances.front().accepted) {
    unfound_ = detection.instances.front();
  }
}

bool ObjectTracker::redetectionDue() const {
  return confirm_detection_ ||
         (params_.redetect_every > 0 && frames_since_detection_ + 1 >= params_.redetect_every);
}

}  // namespace stocs
