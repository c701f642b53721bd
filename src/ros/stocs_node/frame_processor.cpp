#include "stocs_ros/stocs_node/frame_processor.h"

#include <algorithm>

namespace stocs_ros {
namespace {

bool sameParams(const stocs::GeometricSegmentationParams& a,
                const stocs::GeometricSegmentationParams& b) {
  const auto& schema = stocs::GeometricSegmentationParams::schema();
  const auto described_a = schema.describe(a), described_b = schema.describe(b);
  return std::equal(described_a.begin(), described_a.end(), described_b.begin(),
                    [](const auto& x, const auto& y) { return x.second == y.second; });
}

}  // namespace

FrameProcessor::FrameProcessor(ros::NodeHandle& pnh, NodeStatistics& statistics)
    : statistics_(statistics), output_(pnh) {}

FrameResult FrameProcessor::track(const QueuedJob& queued) {
  const EstimationSetup& setup = *queued.setup;
  if (!stream_tracker_ || tracked_models_ != setup.models) {
    stream_tracker_.emplace(setup.config.tracking);  // a reload may change every object
    tracked_models_ = setup.models;
  } else {
    stream_tracker_->setParams(setup.config.tracking);  // runtime settings keep the tracks
  }
  FrameResult result =
      trackJob(queued.job, queued.setup, *stream_tracker_, segmenter(setup.config));
  if (const std::optional<std::string> error = stream_tracker_->takeDetectionError()) {
    ROS_ERROR_THROTTLE(kWarnPeriod, "stocs: background detection failed: %s", error->c_str());
  }
  return result;
}

FrameResult FrameProcessor::process(const QueuedJob& queued) {
  // ~estimate calls detect: a call on an older frame or on given inputs must not move the tracks.
  const bool tracking = !queued.requested && queued.setup->config.tracking.enabled;
  FrameResult result = tracking
                           ? track(queued)
                           : detectJob(queued.job, *queued.setup, segmenter(queued.setup->config));
  const OutputConfig& output = queued.setup->config.output;
  output_frame_.express(result, output.frame, output.transform_timeout);
  output_.publish(result, *queued.setup, queued.timeline);
  statistics_.poses(foundPoses(result).size(), rejectedPoses(result).size());
  if (result.tracking) statistics_.tracking(*result.tracking);
  if (!queued.requested) statistics_.estimated();
  return result;
}

void FrameProcessor::onFrameError(std::exception_ptr error) {
  statistics_.rejected(rejectionKind(error));
  try {
    std::rethrow_exception(error);
  } catch (const std::exception& e) {
    ROS_ERROR_THROTTLE(kWarnPeriod, "stocs: frame rejected: %s (counts on ~statistics)", e.what());
  }
}

stocs::GeometricSegmenter* FrameProcessor::segmenter(const NodeConfig& config) {
  if (config.input.probability != ProbabilitySource::kGeometric) return nullptr;
  if (!geometric_ || !sameParams(geometric_->params(), config.input.geometric)) {
    geometric_.emplace(config.input.geometric);
  }
  return &*geometric_;
}

}  // namespace stocs_ros
