#pragma once
// The segmentation a robot's network publishes (a label image, instance masks, 2D boxes) turned
// into the per-object probability maps of a frame (stocs/io/segmentation_inputs.h), and made into
// messages for the scene publisher. Errors are stocs::InputError naming the input ("label image:
// ...", "instance masks: ...", "boxes: ...").

#include <sensor_msgs/Image.h>
#include <stocs_ros/Detection2DArray.h>
#include <stocs_ros/InstanceMaskArray.h>

#include <map>
#include <opencv2/core.hpp>
#include <vector>

#include "stocs/io/segmentation_inputs.h"
#include "stocs_ros/common/node_config.h"

namespace stocs_ros {

/// A frame's segmentation messages: the one of config.input.probability is set.
struct SegmentationMessages {
  sensor_msgs::ImageConstPtr labels;            ///< labels: class per pixel (mono8, mono16)
  sensor_msgs::ImageConstPtr label_confidence;  ///< labels, optional
  InstanceMaskArrayConstPtr masks;
  Detection2DArrayConstPtr boxes;
};

/// The masks of a message (views of its images: keep `msg` alive).
std::vector<stocs::InstanceMask> masksFromMsg(const InstanceMaskArrayConstPtr& msg);
/// The boxes of a message.
std::vector<stocs::BoxDetection> boxesFromMsg(const Detection2DArray& msg);

/// Per configured object (index as in config.objects; empty but for `objects`) the probability
/// map of its class (NodeConfig::classOf) in an image of `size` (the cloud's) from the message of
/// config.input.probability. Throws InputError naming the input when it is missing or bad.
std::vector<cv::Mat> probabilitiesFromSegmentation(const SegmentationMessages& messages,
                                                   const std::vector<size_t>& objects,
                                                   const NodeConfig& config, cv::Size size);

/// Messages of a BOP frame's detections (class ids: object ids), each class id replaced by
/// `class_of[id]`; detections of ids missing from `class_of` are left out (label pixels: 0).
sensor_msgs::ImagePtr labelsToMsg(const cv::Mat& labels, const std::map<int, int>& class_of);
InstanceMaskArrayPtr masksToMsg(const std::vector<stocs::InstanceMask>& masks,
                                const std::map<int, int>& class_of);
Detection2DArrayPtr boxesToMsg(const std::vector<stocs::BoxDetection>& boxes,
                               const std::map<int, int>& class_of);

}  // namespace stocs_ros
