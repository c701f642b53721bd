#pragma once
// One estimation on one input frame: converts the frame's messages (see cloud_conversion.h and
// image_conversion.h) into a stocs::Frame, or segments its depth (input.probability geometric),
// and runs the core's frame loop (stocs::estimateFrame) on
// the requested objects.

#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/Header.h>

#include <memory>
#include <optional>
#include <vector>

#include "stocs/estimation/frame.h"
#include "stocs/segmentation/geometric_segmentation.h"
#include "stocs/tracking/stream_tracker.h"
#include "stocs_ros/common/segmentation_conversion.h"
#include "stocs_ros/stocs_node/estimation_setup.h"

namespace stocs_ros {

/// One input frame as received: messages are shared, never copied.
struct FrameMessages {
  sensor_msgs::PointCloud2ConstPtr cloud;       ///< input.source: cloud
  sensor_msgs::ImageConstPtr depth;             ///< input.source: depth ...
  sensor_msgs::CameraInfoConstPtr camera_info;  ///< ... with its camera_info
  /// Per configured object (index as in config.objects); null where the frame has none.
  std::vector<sensor_msgs::ImageConstPtr> probabilities;
  sensor_msgs::ImageConstPtr multichannel;  ///< input.probability: multichannel
  sensor_msgs::ImageConstPtr boundary;      ///< optional instance boundary map
  sensor_msgs::ImageConstPtr colour;        ///< optional colour image registered with the depth
  SegmentationMessages segmentation;        ///< input.probability: labels, masks or boxes

  /// The header of the cloud or depth image: the outputs' frame and stamp.
  const std_msgs::Header& header() const;
};

struct EstimationJob {
  FrameMessages frame;
  std::vector<size_t> objects;        ///< indices into config.objects
  std::optional<double> time_budget;  ///< seconds per object, instead of the configured one
  /// The stamp of the frame the synchronizer matched before this one (tracking measures input
  /// gaps with it, not the time estimation took); none for the first frame and ~estimate calls.
  std::optional<ros::Time> previous_input;
};

struct ObjectOutcome {
  size_t object = 0;  ///< index into config.objects
  stocs::PoseEstimate estimate;
  /// Per instance of `estimate` when it was tracked (trackJob); empty when detected.
  std::vector<stocs::TrackState> states;
};

struct FrameResult {
  std_msgs::Header header;
  std::vector<ObjectOutcome> objects;             ///< one per requested object, found or not
  std::optional<stocs::TrackingCounts> tracking;  ///< when tracked (trackJob)
};

/// The job's messages as the core's frame: cloud, colour (the colour image, else the cloud's rgb
/// field), intrinsics, probability maps by object name, boundary; errors as detectJob's.
stocs::Frame convertFrame(const EstimationJob& job, const NodeConfig& config);

/// convertFrame, and with input.probability geometric each requested object's map made from the
/// depth by `geometric` (which must then be given): stocs::setGeometricProbabilities. Its errors
/// are named "geometric segmentation: ...".
stocs::Frame estimationFrame(const EstimationJob& job, const EstimationSetup& setup,
                             stocs::GeometricSegmenter* geometric);

/// Throws stocs::InputError naming the input at fault (cloud, an object's probability image, the
/// boundary map, the colour image, the geometric segmentation) for bad encodings, sizes or
/// parameters. `geometric`: as estimationFrame's.
FrameResult detectJob(const EstimationJob& job, const EstimationSetup& setup,
                      stocs::GeometricSegmenter* geometric = nullptr);

/// The job's objects tracked by `tracker` (config.tracking) as the frame at the header's stamp:
/// followed in the frame, detected in the background (stocs::StreamTracker, which holds `setup`
/// while it detects); errors and `geometric` as detectJob's.
FrameResult trackJob(const EstimationJob& job, const std::shared_ptr<const EstimationSetup>& setup,
                     stocs::StreamTracker& tracker, stocs::GeometricSegmenter* geometric = nullptr);

}  // namespace stocs_ros
