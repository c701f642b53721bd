#include "stocs/tracking/stream_tracker.h"

#include <omp.h>

#include <algorithm>
#include <exception>
#include <utility>

namespace stocs {

StreamTracker::StreamTracker(const TrackingParams& params) : tracker_(params) {
  thread_ = std::thread([this] { run(); });
}

StreamTracker::~StreamTracker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

FrameTracking StreamTracker::track(std::shared_ptr<const Frame> frame,
                                   const std::vector<FrameObject>& objects,
                                   const PipelineParams& params, double stamp,
                                   std::optional<double> previous_input,
                                   std::shared_ptr<const void> keep) {
  // A stream's first frame, and one that ends the tracks, is detected in place: a detection in
  // the background would be merged only into the next frame, which a single frame (an ~estimate
  // like use) never sends and an input slower than max_gap ends again.
  if (!tracker_.started() || tracker_.timeJumped(stamp, previous_input)) {
    return tracker_.track(*frame, objects, params, stamp, previous_input);
  }
  std::optional<FrameDetection> detection;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    detection.swap(done_);
  }
  FrameTracking out = tracker_.follow(*frame, objects, params, stamp, previous_input,
                                      detection ? &*detection : nullptr);
  std::lock_guard<std::mutex> lock(mutex_);
  startDetection(frame, objects, params, std::move(keep));
  return out;
}

void StreamTracker::startDetection(const std::shared_ptr<const Frame>& frame,
                                   const std::vector<FrameObject>& objects,
                                   const PipelineParams& params, std::shared_ptr<const void> keep) {
  if (running_) return;
  std::vector<FrameObject> wanted = tracker_.detectionWanted(objects);
  if (wanted.empty()) return;
  PipelineParams detection_params = params;
  const int threads = params.stocs.threads > 0 ? params.stocs.threads : omp_get_max_threads();
  detection_params.stocs.threads = std::max(1, threads - 1);
  job_ = Job{frame, std::move(wanted), detection_params, tracker_.generation(), std::move(keep)};
  running_ = true;
  wake_.notify_one();
}

void StreamTracker::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stopping_ || job_; });
    if (stopping_) return;
    std::optional<Job> job;
    job.swap(job_);
    lock.unlock();
    FrameDetection detection{job->generation, {}};
    std::optional<std::string> error;
    try {
      detection.objects = estimateFrame(*job->frame, job->objects, job->params);
    } catch (const std::exception& e) {
      error = e.what();
    }
    job.reset();  // the frame and what the models belong to are no longer needed
    lock.lock();
    if (error) {
      error_ = std::move(error);
    } else {
      done_ = std::move(detection);
    }
    running_ = false;
    idle_.notify_all();
  }
}

void StreamTracker::waitForDetection() {
  std::unique_lock<std::mutex> lock(mutex_);
  idle_.wait(lock, [this] { return !running_; });
}

std::optional<std::string> StreamTracker::takeDetectionError() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::optional<std::string> out;
  out.swap(error_);
  return out;
}

}  // namespace stocs
