#include "stocs/tracking/frame_tracker.h"

namespace stocs {

FrameTracker::FrameTracker(const TrackingParams& params) : params_(params) {
  params_.validate();
}

void FrameTracker::reset() {
  objects_.clear();
  last_stamp_.reset();
}

bool FrameTracker::timeJumped(double stamp, std::optional<double> previous_input) const {
  return last_stamp_ &&
         (stamp < *last_stamp_ || stamp - previous_input.value_or(*last_stamp_) > params_.max_gap);
}

FrameTracking FrameTracker::track(const Frame& frame, const std::vector<FrameObject>& objects,
                                  const PipelineParams& params, double stamp,
                                  std::optional<double> previous_input) {
  FrameTracking out;
  out.counts.reset = timeJumped(stamp, previous_input);
  if (out.counts.reset) reset();
  const double dt = last_stamp_ ? stamp - *last_stamp_ : 0.0;
  // estimateFrame checks each object's input and calls the estimator for the objects in order.
  std::vector<ObjectTracking> tracking;
  auto next = objects.begin();
  bool redetection_taken = false;  // one scheduled full detection a frame
  const ObjectEstimator step = [&](const ObjectInput& in) {
    ObjectTracker& tracker = objects_.try_emplace((next++)->name, params_).first->second;
    const bool may_redetect = !redetection_taken;
    redetection_taken = redetection_taken || tracker.redetectionDue();
    tracking.push_back(tracker.update(in, dt, may_redetect));
    return tracking.back().estimate;
  };
  std::vector<ObjectResult> results = estimateFrame(frame, objects, params, step);
  last_stamp_ = stamp;
  for (size_t k = 0; k < results.size(); ++k) {
    ObjectTracking& t = tracking[k];
    for (TrackState s : t.states) {
      out.counts.tracked += s == TrackState::kTracked;
      out.counts.redetected += s == TrackState::kRedetected;
      out.counts.lost += s == TrackState::kLost;
    }
    out.counts.detections += t.detected;
    out.objects.push_back({std::move(results[k]), std::move(t.states), t.detected});
  }
  return out;
}

}  // namespace stocs
