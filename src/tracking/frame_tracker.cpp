#include "stocs/tracking/frame_tracker.h"

#include <omp.h>

#include <algorithm>
#include <exception>

#include "stocs/util/cpu_time.h"

namespace stocs {
namespace {

/// Runs `step(k)` for every object, objects in parallel (each on one thread: a box is too small to
/// share); the CPU time each took. Errors are thrown after all have run, the first object's first,
/// named.
template <class Step>
std::vector<double> inParallel(const std::vector<FrameObject>& objects, int threads, Step step) {
  const int n = static_cast<int>(objects.size());
  std::vector<double> cpu(objects.size(), 0.0);
  std::vector<std::exception_ptr> errors(objects.size());
#pragma omp parallel for schedule(dynamic) num_threads(std::max(1, std::min(threads, n)))
  for (int k = 0; k < n; ++k) {
    try {
      const double start = threadCpuSeconds();
      step(k);
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

int threadCount(const PipelineParams& params) {
  return params.stocs.threads > 0 ? params.stocs.threads : omp_get_max_threads();
}

/// Adds one object's outcome of the frame to `out`.
void add(FrameTracking& out, const std::string& name, ObjectTracking t, double cpu_seconds) {
  for (TrackState s : t.states) {
    out.counts.tracked += s == TrackState::kTracked;
    out.counts.redetected += s == TrackState::kRedetected;
    out.counts.lost += s == TrackState::kLost;
    out.counts.hidden += s == TrackState::kHidden;
  }
  out.counts.detections += t.detected;
  ObjectResult result{name, std::move(t.estimate), cpu_seconds};
  out.objects.push_back({std::move(result), std::move(t.states), t.detected});
}

}  // namespace

FrameTracker::FrameTracker(const TrackingParams& params) : params_(params) {
  params_.validate();
}

void FrameTracker::setParams(const TrackingParams& params) {
  params.validate();
  params_ = params;
  for (auto& [name, tracker] : objects_) tracker.setParams(params);
}

void FrameTracker::reset() {
  objects_.clear();
  last_stamp_.reset();
  ++generation_;
}

bool FrameTracker::timeJumped(double stamp, std::optional<double> previous_input) const {
  return last_stamp_ &&
         (stamp < *last_stamp_ || stamp - previous_input.value_or(*last_stamp_) > params_.max_gap);
}

double FrameTracker::begin(FrameTracking& out, double stamp, std::optional<double> previous_input) {
  out.counts.reset = timeJumped(stamp, previous_input);
  if (out.counts.reset) reset();
  const double dt = last_stamp_ ? stamp - *last_stamp_ : 0.0;
  last_stamp_ = stamp;
  return dt;
}

FrameTracker::Inputs FrameTracker::inputs(const Frame& frame, const CameraIntrinsics& camera,
                                          const std::vector<FrameObject>& objects,
                                          const PipelineParams& params) {
  Inputs out;
  for (const FrameObject& object : objects) {
    forObject(object.name,
              [&] { out.inputs.push_back(objectInput(frame, camera, object, params)); });
    out.trackers.push_back(&objects_.try_emplace(object.name, params_).first->second);
  }
  return out;
}

FrameTracking FrameTracker::track(const Frame& frame, const std::vector<FrameObject>& objects,
                                  const PipelineParams& requested, double stamp,
                                  std::optional<double> previous_input) {
  const PipelineParams params = paramsForMaps(frame, requested);
  FrameTracking out;
  const double dt = begin(out, stamp, previous_input);
  const CameraIntrinsics camera = frameCamera(frame);
  Inputs in = inputs(frame, camera, objects, params);
  std::vector<char> may_redetect;
  bool redetection_taken = false;  // one scheduled full detection a frame
  for (ObjectTracker* tracker : in.trackers) {
    may_redetect.push_back(!redetection_taken);
    redetection_taken = redetection_taken || tracker->redetectionDue();
  }
  const std::vector<double> follow_cpu = inParallel(objects, threadCount(params), [&](int k) {
    in.trackers[k]->follow(in.inputs[k], dt, may_redetect[k]);
  });
  // Searches and detections one object after the other, each with every thread.
  for (size_t k = 0; k < objects.size(); ++k) {
    const double cpu_start = processCpuSeconds();
    ObjectTracking t;
    forObject(objects[k].name, [&] { t = in.trackers[k]->conclude(); });
    add(out, objects[k].name, std::move(t), follow_cpu[k] + processCpuSeconds() - cpu_start);
  }
  explain(frame, camera, objects, params, out);
  return out;
}

FrameTracking FrameTracker::follow(const Frame& frame, const std::vector<FrameObject>& objects,
                                   const PipelineParams& requested, double stamp,
                                   std::optional<double> previous_input,
                                   const FrameDetection* detection) {
  const PipelineParams params = paramsForMaps(frame, requested);
  FrameTracking out;
  const double dt = begin(out, stamp, previous_input);
  std::map<std::string, std::vector<int>> merged;  // tracks that took a detected pose, by object
  if (detection && detection->generation == generation_) {
    merged = merge(*detection, objects, params);
  }
  const CameraIntrinsics camera = frameCamera(frame);
  Inputs in = inputs(frame, camera, objects, params);
  std::vector<ObjectTracking> followed(objects.size());
  const std::vector<double> cpu = inParallel(objects, threadCount(params), [&](int k) {
    followed[k] = in.trackers[k]->followOnly(in.inputs[k], dt);
  });
  for (size_t k = 0; k < objects.size(); ++k) {
    const auto m = merged.find(objects[k].name);
    if (m != merged.end()) {
      // Followed from a detected pose: reported as found again by detection.
      followed[k].detected = true;
      for (int t : m->second) {
        if (followed[k].states[t] == TrackState::kTracked) {
          followed[k].states[t] = TrackState::kRedetected;
        }
      }
    }
    add(out, objects[k].name, std::move(followed[k]), cpu[k]);
  }
  explain(frame, camera, objects, params, out);
  return out;
}

void FrameTracker::explain(const Frame& frame, const CameraIntrinsics& camera,
                           const std::vector<FrameObject>& objects, const PipelineParams& params,
                           FrameTracking& out) {
  std::vector<PoseEstimate*> estimates;
  for (TrackedObject& object : out.objects) estimates.push_back(&object.result.estimate);
  explainFrame(frame, camera, objects, estimates, params);
  for (size_t i = 0; i < out.objects.size(); ++i) {
    TrackedObject& object = out.objects[i];
    for (size_t k = 0; k < object.states.size(); ++k) {
      TrackState& state = object.states[k];
      InstancePose& pose = object.result.estimate.instances[k];
      if ((state != TrackState::kTracked && state != TrackState::kRedetected) || pose.accepted) {
        continue;
      }
      --(state == TrackState::kTracked ? out.counts.tracked : out.counts.redetected);
      ++out.counts.lost;
      state = TrackState::kLost;
      pose.rejection = "lost: " + pose.rejection;
      objects_.at(objects[i].name).lose(k);
    }
  }
}

std::map<std::string, std::vector<int>> FrameTracker::merge(const FrameDetection& detection,
                                                            const std::vector<FrameObject>& objects,
                                                            const PipelineParams& params) {
  std::map<std::string, std::vector<int>> merged;
  for (const ObjectResult& result : detection.objects) {
    const auto object = std::find_if(objects.begin(), objects.end(),
                                     [&](const FrameObject& o) { return o.name == result.name; });
    if (object == objects.end()) continue;  // not asked for in this frame: tracks unchanged
    ObjectTracker& tracker = objects_.try_emplace(result.name, params_).first->second;
    merged[result.name] = tracker.merge(result.estimate, *object->model, params);
  }
  return merged;
}

std::vector<FrameObject> FrameTracker::detectionWanted(
    const std::vector<FrameObject>& objects) const {
  std::vector<FrameObject> wanted;
  bool scheduled_taken = false;  // one scheduled full detection at a time
  for (const FrameObject& object : objects) {
    const auto tracker = objects_.find(object.name);
    if (tracker == objects_.end() || tracker->second.untracked()) {
      wanted.push_back(object);
    } else if (tracker->second.redetectionDue() && !scheduled_taken) {
      wanted.push_back(object);
      scheduled_taken = true;
    }
  }
  return wanted;
}

}  // namespace stocs
