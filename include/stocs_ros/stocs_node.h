#pragma once
// The StoCS node's behaviour, shared by the node executable and the nodelet: subscribes the inputs
// in the private namespace, synchronizes them by stamp, hands complete frames to the estimation
// worker, publishes the results, and serves ~estimate and ~reload. Counts what became of every
// input message and frame (node_statistics.h), publishes the counts on ~statistics every second and
// logs them at shutdown.
//
// Threads: subscription callbacks (the caller's callback queue) only synchronize and queue; the
// services run on a queue and thread of their own, so a service waiting for an estimation never
// holds up the subscriptions; estimation and publishing run on the worker thread.

#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_srvs/Trigger.h>
#include <stocs_ros/Estimate.h>

#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "stocs_ros/estimation_setup.h"
#include "stocs_ros/frame_estimation.h"
#include "stocs_ros/job_worker.h"
#include "stocs_ros/node_statistics.h"
#include "stocs_ros/output_publisher.h"
#include "stocs_ros/stamp_synchronizer.h"
#include "stocs_ros/symmetric_pose.h"

namespace stocs_ros {

class StocsNode {
 public:
  /// Reads the configuration file named by ~config ($(dataset) in its paths standing for ~dataset),
  /// prepares the models, subscribes and advertises.
  /// Throws stocs::InputError naming the problem when the configuration or a model is bad.
  explicit StocsNode(ros::NodeHandle pnh);
  ~StocsNode();

  StocsNode(const StocsNode&) = delete;
  StocsNode& operator=(const StocsNode&) = delete;

 private:
  using InputMessage = std::variant<sensor_msgs::PointCloud2ConstPtr, sensor_msgs::ImageConstPtr,
                                    sensor_msgs::CameraInfoConstPtr, InstanceMaskArrayConstPtr,
                                    Detection2DArrayConstPtr>;
  enum class InputKind {
    kCloud,
    kDepth,
    kCameraInfo,
    kProbability,
    kMultichannel,
    kBoundary,
    kLabels,
    kLabelConfidence,
    kMasks,
    kBoxes
  };
  struct Input {
    InputKind kind;
    size_t object;      ///< kProbability: index into config.objects
    std::string topic;  ///< full name, after remapping
  };
  /// A job with the setup it was made for (a reload may swap the node's setup meanwhile).
  struct QueuedJob {
    EstimationJob job;
    std::shared_ptr<const EstimationSetup> setup;
    bool requested = false;  ///< by ~estimate, not a synchronized frame
    uint64_t timeline = 0;   ///< time jumps back before its frame (see OutputPublisher)
  };

  /// Reads the configuration file and prepares its models (start and ~reload).
  std::shared_ptr<const EstimationSetup> loadSetup() const;
  std::shared_ptr<const EstimationSetup> setup() const;
  void subscribeInputs();
  template <class Message>
  void subscribe(size_t input, int queue_size);
  void onMessage(size_t input, const ros::Time& stamp, InputMessage message);
  /// Counts and logs time going back, seen by the synchronizer on a message of `input`.
  void onTimeJump(size_t input, const ros::Time& stamp);
  FrameMessages toFrame(std::vector<InputMessage>& messages, size_t objects) const;
  FrameResult process(const QueuedJob& queued);
  /// The job's frame through the tracker (tracking.enabled), which starts anew with a new setup.
  FrameResult track(const QueuedJob& queued);
  void onBackgroundError(std::exception_ptr error);
  void publishStatistics();
  /// Validates an ~estimate request and queues its job on the worker.
  std::future<FrameResult> requestEstimation(Estimate::Request& request,
                                             const std::shared_ptr<const EstimationSetup>& setup);
  bool onEstimate(Estimate::Request& request, Estimate::Response& response);
  bool onReload(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);

  ros::NodeHandle pnh_;
  std::string config_file_;
  std::string dataset_;  ///< ~dataset: what $(dataset) in the configuration's paths stands for
  mutable std::mutex setup_mutex_;
  std::shared_ptr<const EstimationSetup> setup_;

  std::vector<Input> inputs_;
  std::vector<ros::Subscriber> subscribers_;
  std::mutex sync_mutex_;  // guards sync_, latest_frame_, latest_timeline_ and latest_stamp_
  std::unique_ptr<StampSynchronizer<InputMessage>> sync_;
  std::optional<FrameMessages> latest_frame_;
  uint64_t latest_timeline_ = 0;                ///< time jumps back before latest_frame_
  std::optional<ros::Time> latest_stamp_;       ///< of latest_frame_
  std::unique_ptr<NodeStatistics> statistics_;  // made with the inputs' topics
  ros::Publisher statistics_pub_;
  ros::WallTimer statistics_timer_;

  OutputPublisher output_;
  SymmetricPoseTracker tracker_;  // worker thread only
  /// Worker thread only: the tracks of the frames (never of ~estimate calls), for `tracked_setup_`;
  /// their full detections run on its own thread.
  std::optional<stocs::StreamTracker> frame_tracker_;
  std::shared_ptr<const EstimationSetup> tracked_setup_;

  ros::CallbackQueue service_queue_;
  ros::AsyncSpinner service_spinner_;
  ros::ServiceServer estimate_service_;
  ros::ServiceServer reload_service_;

  // Last: destroyed first, so the worker stops before anything it uses.
  std::unique_ptr<JobWorker<QueuedJob, FrameResult>> worker_;
};

}  // namespace stocs_ros
