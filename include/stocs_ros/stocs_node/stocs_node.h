#pragma once
// The StoCS node, shared by the node executable and the nodelet: its setup (SetupStore), inputs
// (FrameInputs), estimation worker (FrameProcessor on a JobWorker), services (NodeServices),
// runtime settings (RuntimeSettings, dynamic_reconfigure) and statistics (NodeStatistics, published
// on ~statistics every second and logged at shutdown).
//
// Threads: subscription callbacks (the caller's callback queue) only synchronize and queue; the
// services run on a queue and thread of their own; estimation and publishing run on the worker
// thread.

#include <ros/ros.h>

#include <memory>

#include "stocs_ros/common/clock_watch.h"
#include "stocs_ros/stocs_node/frame_inputs.h"
#include "stocs_ros/stocs_node/frame_processor.h"
#include "stocs_ros/stocs_node/node_services.h"
#include "stocs_ros/stocs_node/node_statistics.h"
#include "stocs_ros/stocs_node/runtime_settings.h"
#include "stocs_ros/stocs_node/setup_store.h"
#include "stocs_ros/stocs_node/stocs_node_params.h"

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
  /// Queues a matched frame's job for every object (output.estimate_on_frames), replacing a
  /// waiting one.
  void onFrame(MatchedFrame matched);
  void publishStatistics();

  ros::NodeHandle pnh_;
  ClockWatch clock_watch_{pnh_, "stocs"};  // says so when /use_sim_time waits on no /clock
  StocsNodeParams params_;
  SetupStore setups_;
  FrameInputs inputs_;
  NodeStatistics statistics_;
  ros::Publisher statistics_pub_;
  ros::WallTimer statistics_timer_;
  FrameProcessor processor_;
  // After everything its jobs use, so that it stops before them.
  EstimationWorker worker_;
  std::unique_ptr<RuntimeSettings> settings_;
  std::unique_ptr<NodeServices> services_;
};

}  // namespace stocs_ros
