#include "stocs_ros/stocs_node/stocs_node.h"

#include <diagnostic_msgs/DiagnosticArray.h>
#include <fmt/format.h>

#include "stocs/util/error.h"
#include "stocs_ros/common/schema_params.h"

namespace stocs_ros {
namespace {

constexpr double kStatisticsPeriod = 1.0;  // seconds between ~statistics messages

/// The private parameters, ~config set; throws stocs::InputError naming a bad one.
StocsNodeParams readParams(const ros::NodeHandle& pnh) {
  StocsNodeParams params;
  readSchemaParams(pnh, StocsNodeParams::schema(), params);
  if (params.config.empty()) {
    throw stocs::InputError(
        fmt::format("parameter {} (the configuration file) is not set", pnh.resolveName("config")));
  }
  return params;
}

}  // namespace

StocsNode::StocsNode(ros::NodeHandle pnh)
    : pnh_(pnh),
      params_(readParams(pnh)),
      setups_(params_.config, params_.dataset),
      inputs_(pnh_, setups_.current()->config),
      statistics_(inputs_.topics()),
      statistics_pub_(pnh_.advertise<diagnostic_msgs::DiagnosticArray>("statistics", 1, true)),
      processor_(pnh_, statistics_),
      worker_([this](const QueuedJob& q) { return processor_.process(q); },
              [this](std::exception_ptr e) { processor_.onFrameError(e); }) {
  inputs_.subscribe(statistics_, [this](MatchedFrame matched) { onFrame(std::move(matched)); });
  settings_ = std::make_unique<RuntimeSettings>(pnh_, setups_);
  services_ = std::make_unique<NodeServices>(pnh_, setups_, inputs_, worker_, statistics_,
                                             [this] { settings_->publishValues(); });
  statistics_timer_ =
      pnh_.createWallTimer(ros::WallDuration(kStatisticsPeriod),
                           [this](const ros::WallTimerEvent&) { publishStatistics(); });
  const NodeConfig& config = setups_.current()->config;
  ROS_INFO("stocs: %zu objects (%s) from %s; waiting for %zu synchronized inputs%s",
           config.objects.size(), config.objectNames().c_str(), setups_.file().c_str(),
           inputs_.topics().size(),
           config.input.probability == ProbabilitySource::kGeometric
               ? " (input.probability geometric: each object's map from the depth alone)"
               : "");
}

StocsNode::~StocsNode() {
  // Stop every source of new jobs, then the worker, so that the final counts are complete.
  statistics_timer_.stop();
  inputs_.shutdown();
  services_.reset();
  worker_.stop();
  ROS_INFO("stocs: at shutdown: %s", statistics_.summary().c_str());
}

void StocsNode::onFrame(MatchedFrame matched) {
  const std::shared_ptr<const EstimationSetup> setup = setups_.current();
  if (!setup->config.output.estimate_on_frames) {
    statistics_.kept();
    return;
  }
  QueuedJob queued{{std::move(matched.frame), {}, std::nullopt, matched.previous_stamp},
                   setup,
                   false,
                   matched.timeline};
  for (size_t i = 0; i < setup->config.objects.size(); ++i) queued.job.objects.push_back(i);
  if (worker_.offer(std::move(queued))) {
    statistics_.replaced();
    ROS_WARN_THROTTLE(kWarnPeriod,
                      "stocs: estimation is slower than the input; a newer frame replaced one "
                      "waiting (counts on ~statistics)");
  }
}

void StocsNode::publishStatistics() {
  diagnostic_msgs::DiagnosticArray msg;
  msg.header.stamp = ros::Time::now();
  msg.status.push_back(statistics_.status(pnh_.getNamespace(), inputs_.queued()));
  statistics_pub_.publish(msg);
}

}  // namespace stocs_ros
