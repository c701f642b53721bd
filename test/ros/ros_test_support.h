#pragma once
// Helpers of the rostest test nodes: waiting for messages, ground truth from the played dataset,
// and pose errors.

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/Pose.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_msgs/TFMessage.h>

#include <Eigen/Geometry>
#include <condition_variable>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "stocs/io/bop_dataset.h"

namespace stocs_ros::test {

/// The first message on `topic` within `timeout` seconds (callbacks must be served by a spinner).
template <class Message>
std::optional<Message> waitForMessage(const std::string& topic, double timeout,
                                      const std::function<bool(const Message&)>& accept = {}) {
  std::mutex mutex;
  std::condition_variable arrived;
  std::optional<Message> received;
  ros::NodeHandle nh;
  const boost::function<void(const boost::shared_ptr<const Message>&)> callback =
      [&](const boost::shared_ptr<const Message>& m) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!received && (!accept || accept(*m))) {
          received = *m;
          arrived.notify_all();
        }
      };
  ros::Subscriber sub = nh.subscribe<Message>(topic, 5, callback);
  std::unique_lock<std::mutex> lock(mutex);
  arrived.wait_for(lock, std::chrono::duration<double>(timeout),
                   [&] { return received.has_value(); });
  std::optional<Message> out = received;
  lock.unlock();
  sub.shutdown();
  return out;
}

/// Calls the service `name` once, on a persistent connection that the client closes after the
/// answer. With roscpp's one-shot calls (ros::service::call) the server closes the connection
/// after answering, and the client may see the hang-up before the answer and report a failure
/// (ros/ros_comm#1976; a CI run on 2026-12-02: the node answered, the call returned false).
template <class Service>
bool callService(const std::string& name, Service& srv) {
  ros::ServiceClient client = ros::NodeHandle().serviceClient<Service>(name, /*persistent=*/true);
  return client.call(srv);
}

/// Image 0 of scene 0 of a generated BOP dataset as the node's inputs: an organized cloud
/// (frame "camera") and the 32FC1 probability image of object 1, stamps unset.
struct InputFrame {
  sensor_msgs::PointCloud2 cloud;
  sensor_msgs::Image probability;
};
InputFrame loadInputFrame(const std::filesystem::path& dataset);

/// The node's ~statistics counters by key (see node_statistics.h).
std::map<std::string, uint64_t> statisticsCounts(const diagnostic_msgs::DiagnosticArray& msg);
/// Messages of `topic` dropped by the synchronizer, all reasons together.
uint64_t droppedMessages(std::map<std::string, uint64_t>& counts, const std::string& topic);

/// Model-to-camera pose (metres) of the first ground-truth instance of `obj_id` in a BOP frame.
Eigen::Isometry3d groundTruthPose(const std::filesystem::path& dataset, int scene, int image,
                                  int obj_id);

/// ADD-S error of `pose` against `truth` (model-to-camera, metres) on the vertices of the dataset's
/// model of `obj_id`, as a fraction of the model's diameter: the acceptance measure of the
/// real-frame tests, which forgives what the shape cannot tell apart.
double addsDiameterRatio(const std::filesystem::path& dataset, int obj_id,
                         const Eigen::Isometry3d& pose, const Eigen::Isometry3d& truth);
/// The same with ADD, which forgives nothing: which way the object faces counts.
double addDiameterRatio(const std::filesystem::path& dataset, int obj_id,
                        const Eigen::Isometry3d& pose, const Eigen::Isometry3d& truth);

/// The image whose ground truth (the scene publisher's gt_ frames) `msg` carries: the one with as
/// many instances as `msg` has transforms, each at its translation in order; -1 when none matches.
int imageOf(const tf2_msgs::TFMessage& msg,
            const std::map<int, std::vector<stocs::BopGtInstance>>& gt);

/// A pose message as an Eigen transform.
Eigen::Isometry3d poseToEigen(const geometry_msgs::Pose& pose);

/// Translation error (metres) and rotation angle (radians) between two poses.
double translationError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);
double rotationError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);

}  // namespace stocs_ros::test
