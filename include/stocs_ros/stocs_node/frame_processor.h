#pragma once
// What the node's estimation worker does with a job: detects its objects (detectJob), or, for the
// frames of a stream with tracking.enabled, tracks them (trackJob with a stocs::StreamTracker that
// starts anew with new models, and takes new tracking settings without ending its tracks; the core
// chooses a symmetric object's equivalent pose); expresses the result in the output frame
// (OutputFrame); publishes it (OutputPublisher) and counts it. With input.probability geometric it
// holds the node's GeometricSegmenter, which frames and ~estimate calls share. Runs on the worker's
// thread only, one job at a time, so it holds no lock.

#include <ros/ros.h>

#include <exception>
#include <memory>
#include <optional>

#include "stocs/tracking/stream_tracker.h"
#include "stocs_ros/stocs_node/estimation_setup.h"
#include "stocs_ros/stocs_node/frame_estimation.h"
#include "stocs_ros/stocs_node/node_statistics.h"
#include "stocs_ros/stocs_node/output_frame.h"
#include "stocs_ros/stocs_node/output_publisher.h"

namespace stocs_ros {

/// A job with the setup it was made for (a reload may swap the node's setup meanwhile).
struct QueuedJob {
  EstimationJob job;
  std::shared_ptr<const EstimationSetup> setup;
  bool requested = false;  ///< by ~estimate, not a synchronized frame
  uint64_t timeline = 0;   ///< time jumps back before its frame (see OutputPublisher)
};

class FrameProcessor {
 public:
  /// Advertises the outputs on `pnh`; counts in `statistics`, which must outlive it.
  FrameProcessor(ros::NodeHandle& pnh, NodeStatistics& statistics);

  FrameResult process(const QueuedJob& queued);
  /// Counts and logs what a frame's job threw (nobody waits for its result).
  void onFrameError(std::exception_ptr error);

 private:
  FrameResult track(const QueuedJob& queued);
  /// With input.probability geometric, the node's one segmenter (made anew when its parameters
  /// change: it keeps PCL's buffers between frames); else null.
  stocs::GeometricSegmenter* segmenter(const NodeConfig& config);

  NodeStatistics& statistics_;
  OutputFrame output_frame_;
  OutputPublisher output_;
  /// The tracks of the frames (never of ~estimate calls), of `tracked_models_`; their full
  /// detections run on a thread of their own.
  std::optional<stocs::StreamTracker> stream_tracker_;
  std::vector<std::shared_ptr<const stocs::PreparedModel>> tracked_models_;
  std::optional<stocs::GeometricSegmenter> geometric_;
};

}  // namespace stocs_ros
