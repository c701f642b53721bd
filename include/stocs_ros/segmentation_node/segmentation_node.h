#pragma once
// The segmentation node: runs a segmentation network exported to ONNX (stocs::SegmentationNetwork)
// on a colour image stream and publishes the per-object probability maps the StoCS node takes, as
// one multi-channel 32FC<n> image (~probability, the objects of ~channels in order) and, while
// subscribed, one 32FC1 image per object (~probability/<object>), each with the colour image's
// header (8UC<n> and 8UC1 with ~probability_depth 8U). Lazy: it subscribes to the colour image only
// while one of its outputs has a subscriber. A bad image is counted and logged (throttled), never
// fatal; a bad configuration or model ends the start with stocs::InputError. docs/ros.md,
// "Segmentation node".

#include <diagnostic_msgs/DiagnosticArray.h>
#include <image_transport/image_transport.h>
#include <ros/ros.h>

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "stocs/segmentation/segmentation_network.h"
#include "stocs_ros/segmentation_node/segmentation_output_params.h"

namespace stocs_ros {

class SegmentationNode {
 public:
  /// Reads the private parameters (the network's, docs/parameters.md) and loads the model.
  explicit SegmentationNode(ros::NodeHandle pnh);

 private:
  void onImage(const sensor_msgs::ImageConstPtr& msg);
  /// The output maps (SegmentationNetwork::outputMaps) at `size` for every output with a
  /// subscriber, each with its publisher.
  std::vector<std::pair<ros::Publisher*, sensor_msgs::ImagePtr>> mapsMessages(
      const std_msgs::Header& header, const cv::Mat& maps, cv::Size size);
  /// Subscribes to the colour image while any output has a subscriber, and only then.
  void updateSubscription();
  void publishStatistics(const ros::TimerEvent&);
  void rejected(const std::string& reason, const std::string& message);

  ros::NodeHandle pnh_;
  image_transport::ImageTransport transport_;
  stocs::SegmentationNetwork network_;
  SegmentationOutputParams output_;
  std::vector<std::pair<std::string, int>> objects_;  ///< name and output channel, in order
  image_transport::Subscriber image_;
  ros::Publisher multichannel_;
  std::vector<ros::Publisher> per_object_;
  ros::Publisher statistics_;
  ros::Timer statistics_timer_;
  std::mutex mutex_;  ///< the subscription and the counters
  uint64_t received_ = 0, segmented_ = 0;
  std::map<std::string, uint64_t> rejected_;  ///< by reason
  double seconds_ = 0;                        ///< segmentation time of the segmented images
};

}  // namespace stocs_ros
