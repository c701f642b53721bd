// The node with `output.frame: base_link` and a static transform base_link -> camera (published
// here): TF, ~poses, ~objects and ~estimate speak of base_link and match the ground truth moved
// there, with the covariance rotated as the poses; a second node on the same inputs without an
// output frame gives the camera-frame answer to compare with; a third asks for a frame TF does not
// know and publishes nothing, naming both frames. A runtime min_confidence change through
// dynamic_reconfigure rejects the object from the next frame without a tracking reset, and a value
// out of range is refused.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <geometry_msgs/PoseArray.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <stocs_ros/Estimate.h>
#include <stocs_ros/ObjectPoseArray.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include <algorithm>

#include "ros_test_support.h"

namespace stocs_ros::test {
namespace {

constexpr double kFirstOutputTimeout = 120;  // seconds: includes preparing an uncached model
std::string g_dataset;
const char* const kCameraFrame = "camera_optical_frame";

/// base_link -> camera: 0.3 m ahead, 1 m up, looking down and to the side.
Eigen::Isometry3d baseFromCamera() {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translate(Eigen::Vector3d(0.3, -0.2, 1.0));
  t.rotate(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) *
           Eigen::AngleAxisd(-2.2, Eigen::Vector3d::UnitX()));
  return t;
}

Estimate::Response callEstimate(const std::string& node, Estimate::Request request) {
  const std::string name = node + "/estimate";
  EXPECT_TRUE(ros::service::waitForService(name, ros::Duration(kFirstOutputTimeout)));
  Estimate srv;
  srv.request = std::move(request);
  EXPECT_TRUE(callService(name, srv)) << name;
  return srv.response;
}

Eigen::Matrix<double, 6, 6> covarianceOf(const ObjectPose& o) {
  Eigen::Matrix<double, 6, 6> c;
  for (int r = 0; r < 6; ++r) {
    for (int k = 0; k < 6; ++k) c(r, k) = o.pose.covariance[static_cast<size_t>(6 * r + k)];
  }
  return c;
}

dynamic_reconfigure::Config setMinConfidence(double value) {
  dynamic_reconfigure::Reconfigure srv;
  dynamic_reconfigure::DoubleParameter p;
  p.name = "min_confidence";
  p.value = value;
  srv.request.config.doubles.push_back(p);
  EXPECT_TRUE(ros::service::waitForService("/stocs/set_parameters", ros::Duration(30)));
  EXPECT_TRUE(callService("/stocs/set_parameters", srv));
  return srv.response.config;
}

/// min_confidence in `config` (a float in the node: compared to the float's precision).
void expectMinConfidence(const dynamic_reconfigure::Config& config, double expected) {
  const auto p = std::find_if(config.doubles.begin(), config.doubles.end(),
                              [](const auto& d) { return d.name == "min_confidence"; });
  ASSERT_NE(p, config.doubles.end()) << "no min_confidence in the answer";
  EXPECT_NEAR(p->value, expected, 1e-6);
}

class RobotFrame : public ::testing::Test {
 protected:
  void SetUp() override { truth_base_ = baseFromCamera() * groundTruthPose(g_dataset, 0, 0, 1); }
  Eigen::Isometry3d truth_base_;
};

TEST_F(RobotFrame, PosesAndTfAreInTheOutputFrameNearTheMovedTruth) {
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);  // before the poses: TF at their stamp is kept
  const auto objects =
      waitForMessage<ObjectPoseArray>("/stocs/objects", kFirstOutputTimeout,
                                      [](const ObjectPoseArray& m) { return !m.objects.empty(); });
  ASSERT_TRUE(objects) << "no /stocs/objects with a pose";
  EXPECT_EQ(objects->header.frame_id, "base_link");
  EXPECT_LT(translationError(poseToEigen(objects->objects[0].pose.pose), truth_base_), 0.005);
  EXPECT_LT(rotationError(poseToEigen(objects->objects[0].pose.pose), truth_base_), 0.05);

  const auto poses = waitForMessage<geometry_msgs::PoseArray>(
      "/stocs/poses", 30, [](const geometry_msgs::PoseArray& m) { return !m.poses.empty(); });
  ASSERT_TRUE(poses);
  EXPECT_EQ(poses->header.frame_id, "base_link");
  EXPECT_LT(translationError(poseToEigen(poses->poses[0]), truth_base_), 0.005);

  const Eigen::Isometry3d tf_pose = tf2::transformToEigen(
      buffer.lookupTransform("base_link", "box", poses->header.stamp, ros::Duration(10)));
  EXPECT_LT(translationError(tf_pose, truth_base_), 0.005);
  EXPECT_LT(rotationError(tf_pose, truth_base_), 0.05);
}

TEST_F(RobotFrame, TheServiceAnswersInTheOutputFrameWithTheCovarianceRotated) {
  // The same cloud to the node in base_link and to the one in the camera frame: one estimate,
  // expressed in two frames.
  const auto cloud =
      waitForMessage<sensor_msgs::PointCloud2>("/camera/depth_registered/points", 30);
  const auto probability = waitForMessage<sensor_msgs::Image>("/segmentation/probability/box", 30);
  ASSERT_TRUE(cloud && probability);
  Estimate::Request request;
  request.cloud = *cloud;
  request.probabilities = {*probability};
  const Estimate::Response base = callEstimate("/stocs", request);
  const Estimate::Response camera = callEstimate("/stocs_camera", request);
  ASSERT_TRUE(base.success && camera.success) << base.message << " / " << camera.message;
  ASSERT_EQ(base.result.objects.size(), 1u);
  ASSERT_EQ(camera.result.objects.size(), 1u);
  EXPECT_EQ(base.result.header.frame_id, "base_link");
  EXPECT_EQ(camera.result.header.frame_id, kCameraFrame);
  const Eigen::Isometry3d moved =
      baseFromCamera() * poseToEigen(camera.result.objects[0].pose.pose);
  const Eigen::Isometry3d in_base = poseToEigen(base.result.objects[0].pose.pose);
  EXPECT_LT(translationError(in_base, moved), 1e-4);
  EXPECT_LT(rotationError(in_base, moved), 1e-3);

  Eigen::Matrix<double, 6, 6> rotate = Eigen::Matrix<double, 6, 6>::Zero();
  rotate.topLeftCorner<3, 3>() = baseFromCamera().rotation();
  rotate.bottomRightCorner<3, 3>() = baseFromCamera().rotation();
  const Eigen::Matrix<double, 6, 6> expected =
      rotate * covarianceOf(camera.result.objects[0]) * rotate.transpose();
  const Eigen::Matrix<double, 6, 6> published = covarianceOf(base.result.objects[0]);
  EXPECT_GT(expected.norm(), 0);
  EXPECT_LT((published - expected).norm(), 1e-3 * expected.norm()) << published << "\n\n"
                                                                   << expected;
  // Rotated, not copied: the camera-frame covariance is not the base_link one.
  EXPECT_GT((covarianceOf(camera.result.objects[0]) - published).norm(), 1e-2 * expected.norm());
}

TEST_F(RobotFrame, AMissingTransformGivesAnErrorNamingBothFramesAndNoPose) {
  // The node asked for "nowhere" matches frames but publishes none of them.
  EXPECT_FALSE(waitForMessage<ObjectPoseArray>("/stocs_nowhere/objects", 15));
  const auto statistics = waitForMessage<diagnostic_msgs::DiagnosticArray>(
      "/stocs_nowhere/statistics", 10, [](const diagnostic_msgs::DiagnosticArray& m) {
        std::map<std::string, uint64_t> counts = statisticsCounts(m);
        return counts["frames rejected: output frame"] > 0;
      });
  EXPECT_TRUE(statistics) << "no frame counted as rejected for the output frame";
  const Estimate::Response r = callEstimate("/stocs_nowhere", Estimate::Request());
  EXPECT_FALSE(r.success);
  EXPECT_NE(r.message.find(std::string("no transform from '") + kCameraFrame + "' to 'nowhere'"),
            std::string::npos)
      << r.message;
  EXPECT_TRUE(r.result.objects.empty());
}

TEST_F(RobotFrame, ARuntimeMinConfidenceRejectsTheObjectWithoutATrackingReset) {
  const auto before =
      waitForMessage<ObjectPoseArray>("/stocs/objects", kFirstOutputTimeout,
                                      [](const ObjectPoseArray& m) { return !m.objects.empty(); });
  ASSERT_TRUE(before);
  const auto counts_before =
      waitForMessage<diagnostic_msgs::DiagnosticArray>("/stocs/statistics", 5);
  ASSERT_TRUE(counts_before);

  // Out of range: refused, the setting kept (the default, config/default.yaml's).
  constexpr double kDefault = 0.25;
  expectMinConfidence(setMinConfidence(1.5), kDefault);
  // Above any confidence: the next frame rejects the object, still followed.
  expectMinConfidence(setMinConfidence(1.0), 1.0);
  const auto after = waitForMessage<ObjectPoseArray>(
      "/stocs/objects", 10, [](const ObjectPoseArray& m) { return !m.rejected.empty(); });
  ASSERT_TRUE(after) << "the object was never rejected after the change";
  EXPECT_TRUE(after->objects.empty());
  EXPECT_EQ(after->rejected[0].name, "box");
  const auto counts_after =
      waitForMessage<diagnostic_msgs::DiagnosticArray>("/stocs/statistics", 5);
  ASSERT_TRUE(counts_after);
  EXPECT_EQ(statisticsCounts(*counts_after)["tracking resets"],
            statisticsCounts(*counts_before)["tracking resets"]);

  expectMinConfidence(setMinConfidence(kDefault), kDefault);
  EXPECT_TRUE(waitForMessage<ObjectPoseArray>(
      "/stocs/objects", 10, [](const ObjectPoseArray& m) { return !m.objects.empty(); }));
}

}  // namespace
}  // namespace stocs_ros::test

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_robot_frame");
  ros::NodeHandle pnh("~");
  pnh.getParam("dataset", stocs_ros::test::g_dataset);
  tf2_ros::StaticTransformBroadcaster broadcaster;
  geometry_msgs::TransformStamped t = tf2::eigenToTransform(stocs_ros::test::baseFromCamera());
  t.header.stamp = ros::Time::now();
  t.header.frame_id = "base_link";
  t.child_frame_id = stocs_ros::test::kCameraFrame;
  broadcaster.sendTransform(t);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
