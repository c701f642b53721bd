#pragma once
// The node's services: ~estimate (the latest synchronized frame, or inputs given in the request,
// estimated now for the requested objects, ahead of waiting frames) and ~reload (the configuration
// file read again). They run on a callback queue and thread of their own, so a service waiting for
// an estimation never holds up the subscriptions.

#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <stocs_ros/Estimate.h>

#include <functional>
#include <future>
#include <memory>

#include "stocs_ros/stocs_node/frame_inputs.h"
#include "stocs_ros/stocs_node/frame_processor.h"
#include "stocs_ros/stocs_node/job_worker.h"
#include "stocs_ros/stocs_node/node_statistics.h"
#include "stocs_ros/stocs_node/setup_store.h"

namespace stocs_ros {

using EstimationWorker = JobWorker<QueuedJob, FrameResult>;

class NodeServices {
 public:
  /// Advertises ~estimate and ~reload on `pnh`; what it is given must outlive it. `on_reload`
  /// runs after a successful ~reload.
  NodeServices(const ros::NodeHandle& pnh, SetupStore& setups, FrameInputs& inputs,
               EstimationWorker& worker, NodeStatistics& statistics,
               std::function<void()> on_reload);
  ~NodeServices() { shutdown(); }

  /// Stops serving; a call under way finishes first.
  void shutdown();

 private:
  /// Validates an ~estimate request and queues its job on the worker.
  std::future<FrameResult> requestEstimation(Estimate::Request& request,
                                             const std::shared_ptr<const EstimationSetup>& setup);
  bool onEstimate(Estimate::Request& request, Estimate::Response& response);
  bool onReload(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);

  SetupStore& setups_;
  FrameInputs& inputs_;
  EstimationWorker& worker_;
  NodeStatistics& statistics_;
  std::function<void()> on_reload_;
  ros::CallbackQueue queue_;
  ros::AsyncSpinner spinner_;
  ros::ServiceServer estimate_;
  ros::ServiceServer reload_;
};

}  // namespace stocs_ros
