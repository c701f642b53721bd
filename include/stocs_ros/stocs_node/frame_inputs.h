#pragma once
// The node's inputs: subscribes them in the private namespace (the depth input, the segmentation
// in the configured form, the optional boundary map and colour image), matches their messages by
// stamp into frames (StampSynchronizer), keeps the latest frame for ~estimate, and hands every
// matched frame on. Counts received, dropped and matched messages and time jumps in NodeStatistics.
// One lock guards the synchronizer and the latest frame; subscription callbacks may run on several
// threads.

#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "stocs_ros/common/node_config.h"
#include "stocs_ros/common/stamp_synchronizer.h"
#include "stocs_ros/stocs_node/frame_estimation.h"
#include "stocs_ros/stocs_node/node_statistics.h"

namespace stocs_ros {

/// A frame the synchronizer matched.
struct MatchedFrame {
  FrameMessages frame;
  ros::Time stamp;                          ///< the synchronizer's match stamp
  uint64_t timeline = 0;                    ///< time jumps back before it (see OutputPublisher)
  std::optional<ros::Time> previous_stamp;  ///< of the frame matched before it
};

class FrameInputs {
 public:
  /// The inputs `config` names (its input section and objects), resolved in `pnh`'s namespace;
  /// nothing is subscribed yet.
  FrameInputs(ros::NodeHandle pnh, const NodeConfig& config);
  ~FrameInputs() { shutdown(); }

  /// The inputs' resolved topic names, in the synchronizer's order (NodeStatistics' inputs).
  std::vector<std::string> topics() const;
  /// Subscribes every input; each matched frame goes to `on_frame` (outside the lock), counted in
  /// `statistics`, which must outlive the subscriptions.
  void subscribe(NodeStatistics& statistics, std::function<void(MatchedFrame)> on_frame);
  void shutdown();

  /// Calls `use(latest, time_jumps)` under the lock: the latest matched frame (null before the
  /// first) and the time jumps back seen so far. A caller that queues work on the latest frame
  /// does it inside, so that no newer frame is matched and published before it.
  template <class Use>
  auto withLatest(Use use) {
    std::lock_guard<std::mutex> lock(mutex_);
    return use(latest_ ? &*latest_ : nullptr, sync_->timeJumps());
  }
  /// Messages of each input waiting in the synchronizer.
  std::vector<size_t> queued() const;

 private:
  using Message = std::variant<sensor_msgs::PointCloud2ConstPtr, sensor_msgs::ImageConstPtr,
                               sensor_msgs::CameraInfoConstPtr, InstanceMaskArrayConstPtr,
                               Detection2DArrayConstPtr>;
  enum class Kind {
    kCloud,
    kDepth,
    kCameraInfo,
    kProbability,
    kMultichannel,
    kBoundary,
    kColour,
    kLabels,
    kLabelConfidence,
    kMasks,
    kBoxes
  };
  struct Input {
    Kind kind;
    size_t object;      ///< kProbability: index into config.objects
    std::string topic;  ///< full name, after remapping
  };

  void add(const std::string& topic, Kind kind, size_t object = 0);
  template <class M>
  void subscribeTo(size_t input, int queue_size);
  void onMessage(size_t input, const ros::Time& stamp, Message message);
  /// Counts and logs time going back, seen by the synchronizer on a message of `input`.
  void onTimeJump(size_t input, const ros::Time& stamp);
  void logDropped(const std::vector<DroppedMessage>& dropped) const;  // caller holds mutex_
  FrameMessages toFrame(std::vector<Message>& messages) const;

  ros::NodeHandle pnh_;
  const size_t objects_;
  const int queue_size_;
  std::vector<Input> inputs_;
  std::vector<ros::Subscriber> subscribers_;
  NodeStatistics* statistics_ = nullptr;
  std::function<void(MatchedFrame)> on_frame_;

  mutable std::mutex mutex_;  // guards sync_ and latest_
  std::unique_ptr<StampSynchronizer<Message>> sync_;
  std::optional<MatchedFrame> latest_;
};

}  // namespace stocs_ros
