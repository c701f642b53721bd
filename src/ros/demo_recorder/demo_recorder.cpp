#include "stocs_ros/demo_recorder/demo_recorder.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "stocs/io/bop_results.h"
#include "stocs/util/error.h"
#include "stocs_ros/common/instance_name.h"
#include "stocs_ros/common/schema_params.h"

namespace stocs_ros {

DemoRecorder::DemoRecorder(const ros::NodeHandle& pnh) {
  readSchemaParams(pnh, DemoRecorderParams::schema(), params_);
  requireSet(pnh, "results", params_.results);
  subscriber_ = nh_.subscribe("objects", 10, &DemoRecorder::onObjects, this);
  timeout_ = nh_.createWallTimer(
      ros::WallDuration(params_.timeout),
      [this](const ros::WallTimerEvent&) {
        ROS_ERROR("demo: %zu of %d frames of estimates within %.0f s; is the node running?",
                  latencies_.size(), params_.frames, params_.timeout);
        ros::shutdown();
      },
      true);
}

namespace {

const char* stateName(uint8_t state) {
  switch (state) {
    case ObjectPose::TRACKED:
      return "tracked";
    case ObjectPose::REDETECTED:
      return "redetected";
    default:
      return "detected";
  }
}

}  // namespace

void DemoRecorder::onObjects(const ObjectPoseArray::ConstPtr& message) {
  const double latency = (ros::Time::now() - message->header.stamp).toSec();
  latencies_.push_back(latency);
  fmt::print("frame {} of {}: {} object(s), latency {:.0f} ms\n", latencies_.size(), params_.frames,
             message->objects.size(), 1000 * latency);
  for (const ObjectPose& o : message->objects) {
    const auto& p = o.pose.pose.position;
    fmt::print(
        "  {} (id {}): {}, confidence {:.2f}, score {:.4f}, t [{:.1f} {:.1f} {:.1f}] mm (std "
        "{:.1f} mm), {:.0f} ms, {} hypotheses\n",
        instanceName(o.name, o.instance), o.id, stateName(o.state), o.confidence, o.score,
        1000 * p.x, 1000 * p.y, 1000 * p.z,
        1000 * std::sqrt(o.pose.covariance[0] + o.pose.covariance[7] + o.pose.covariance[14]),
        1000 * o.estimation_time, o.hypotheses_verified);
  }
  for (const RejectedObject& r : message->rejected) {
    fmt::print("  {} (id {}): rejected, {}\n", instanceName(r.name, r.instance), r.id, r.reason);
  }
  if (static_cast<int>(latencies_.size()) < params_.frames) return;
  std::vector<double> sorted = latencies_;
  std::sort(sorted.begin(), sorted.end());
  // Nearest-rank percentiles: with few frames, p95 is the maximum.
  const auto percentile = [&](double q) {
    const size_t rank = static_cast<size_t>(std::ceil(q * static_cast<double>(sorted.size())));
    return 1000 * sorted[std::max<size_t>(rank, 1) - 1];
  };
  fmt::print(
      "latency from input stamp to estimates over {} frames: p50 {:.0f} ms, p95 {:.0f} ms, max "
      "{:.0f} ms\n",
      sorted.size(), percentile(0.5), percentile(0.95), 1000 * sorted.back());
  writeResults(*message, latency);
  ros::shutdown();
}

void DemoRecorder::writeResults(const ObjectPoseArray& message, double latency) const {
  std::vector<stocs::BopResult> rows;
  for (const ObjectPose& o : message.objects) {
    stocs::BopResult r;
    r.scene_id = params_.scene;
    r.im_id = params_.image;
    r.obj_id = o.id;
    r.score = o.score;
    const geometry_msgs::Pose& pose = o.pose.pose;
    const auto& q = pose.orientation;
    r.R = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix();
    r.t_mm = 1000.0 * Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
    r.time = latency;
    rows.push_back(r);
  }
  stocs::writeBopResults(params_.results, rows);
  fmt::print("results of the last frame: {}\n", params_.results);
}

}  // namespace stocs_ros
