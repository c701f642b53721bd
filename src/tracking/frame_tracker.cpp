#include "stocs/tracking/frame_tracker.h"

#include <omp.h>

#include <algorithm>
#include <exception>

#include "stocs/util/cpu_time.h"

namespace stocs {
namespace {

/// Follows the tracks of every object, objects in parallel (each follows on one thread: a box is
/// too small to share); the CPU time each took. Errors are thrown after all have run, the first
/// object's first, named.
std::vector<double> followAll(const std::vector<ObjectTracker*>& trackers,
                              const std::vector<FrameObject>& objects,
                              const std::vector<ObjectInput>& inputs,
                              const std::vector<char>& may_redetect, double dt, int threads) {
  const int n = static_cast<int>(trackers.size());
  std::vector<double> cpu(trackers.size(), 0.0);
  std::vector<std::exception_ptr> errors(trackers.size());
#pragma omp parallel for schedule(dynamic) num_threads(std::max(1, std::min(threads, n)))
  for (int k = 0; k < n; ++k) {
    try {
      const double start = threadCpuSeconds();
      trackers[k]->follow(inputs[k], dt, may_redetect[k]);
      cpu[k] = threadCpuSeconds() - start;
    } catch (...) {
      errors[k] = std::current_exception();
    }
  }
  for (int k = 0; k < n; ++k) {
    if (errors[k]) forObject(objects[k].name, [&] { std::rethrow_exception(errors[k]); });
  }
  return cpu;
}

}  // namespace

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
  const CameraIntrinsics camera = frameCamera(frame);
  std::vector<ObjectInput> inputs;
  std::vector<ObjectTracker*> trackers;
  std::vector<char> may_redetect;
  bool redetection_taken = false;  // one scheduled full detection a frame
  for (const FrameObject& object : objects) {
    forObject(object.name, [&] { inputs.push_back(objectInput(frame, camera, object, params)); });
    trackers.push_back(&objects_.try_emplace(object.name, params_).first->second);
    may_redetect.push_back(!redetection_taken);
    redetection_taken = redetection_taken || trackers.back()->redetectionDue();
  }
  const int threads = params.stocs.threads > 0 ? params.stocs.threads : omp_get_max_threads();
  const std::vector<double> follow_cpu =
      followAll(trackers, objects, inputs, may_redetect, dt, threads);
  last_stamp_ = stamp;
  // Searches and detections one object after the other, each with every thread.
  for (size_t k = 0; k < objects.size(); ++k) {
    const double cpu_start = processCpuSeconds();
    ObjectTracking t;
    forObject(objects[k].name, [&] { t = trackers[k]->conclude(); });
    for (TrackState s : t.states) {
      out.counts.tracked += s == TrackState::kTracked;
      out.counts.redetected += s == TrackState::kRedetected;
      out.counts.lost += s == TrackState::kLost;
    }
    out.counts.detections += t.detected;
    ObjectResult result{objects[k].name, std::move(t.estimate),
                        follow_cpu[k] + processCpuSeconds() - cpu_start};
    out.objects.push_back({std::move(result), std::move(t.states), t.detected});
  }
  return out;
}

}  // namespace stocs
