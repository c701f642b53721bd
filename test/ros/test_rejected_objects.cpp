// The node on a frame holding one of its three configured objects: the box is present; "noise" (its
// map is low background noise with a few blobs) is not, nor "lookalike" (the box 10% smaller, its
// map marking the box fainter than the box's own). The present object gets a TF frame, a finite,
// positive-definite covariance (on ~objects and on its ~pose/box topic) and an uncertainty
// ellipsoid; the absent ones get no TF frame, no ~poses entry and no marker, and ~objects and the
// ~estimate service list them as rejected, with a reason: the look-alike, which alone fits the
// box, "explained by box 0" (issue 45). absent_objects.test runs it with tracking and without.
#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <stocs_ros/Estimate.h>
#include <stocs_ros/ObjectPoseArray.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <Eigen/Cholesky>
#include <algorithm>

#include "ros_test_support.h"

namespace stocs_ros::test {
namespace {

constexpr double kFirstOutputTimeout = 120;  // seconds: includes preparing uncached models
const std::string kNode = "/stocs";
const std::string kFrame = "camera_optical_frame";
const std::vector<std::string> kAbsent = {"noise", "lookalike"};

using Covariance = Eigen::Matrix<double, 6, 6, Eigen::RowMajor>;

/// ~objects once it holds the box.
std::optional<ObjectPoseArray> objectsWithTheBox() {
  return waitForMessage<ObjectPoseArray>(
      kNode + "/objects", kFirstOutputTimeout, [](const ObjectPoseArray& m) {
        return std::any_of(m.objects.begin(), m.objects.end(),
                           [](const ObjectPose& o) { return o.name == "box"; });
      });
}

void expectPositiveDefinite(const boost::array<double, 36>& entries, const std::string& what) {
  const Covariance c = Eigen::Map<const Covariance>(entries.data());
  ASSERT_TRUE(c.allFinite()) << what;
  EXPECT_TRUE(c.isApprox(c.transpose())) << what;
  const Eigen::LLT<Eigen::Matrix<double, 6, 6>> cholesky(c);
  EXPECT_EQ(cholesky.info(), Eigen::Success) << what << ": not positive definite";
  // The box is in plain view: its position is known to well under its size.
  EXPECT_LT(std::sqrt(c.topLeftCorner<3, 3>().trace()), 0.02) << what;
}

const RejectedObject* rejected(const ObjectPoseArray& m, const std::string& name) {
  for (const RejectedObject& r : m.rejected) {
    if (r.name == name) return &r;
  }
  return nullptr;
}

TEST(RejectedObjects, ThePresentObjectHasTfAndACovariance) {
  const auto objects = objectsWithTheBox();
  ASSERT_TRUE(objects) << "no ~objects message with the box";
  const auto box = std::find_if(objects->objects.begin(), objects->objects.end(),
                                [](const ObjectPose& o) { return o.name == "box"; });
  expectPositiveDefinite(box->pose.covariance, "~objects");
  EXPECT_GE(box->confidence, 0.0);
  EXPECT_LE(box->confidence, 1.0);
  EXPECT_EQ(rejected(*objects, "box"), nullptr);

  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  EXPECT_TRUE(buffer.canTransform(kFrame, "box", ros::Time(0), ros::Duration(10)));

  const auto single = waitForMessage<geometry_msgs::PoseWithCovarianceStamped>(kNode + "/pose/box",
                                                                               kFirstOutputTimeout);
  ASSERT_TRUE(single) << "no " << kNode << "/pose/box message";
  EXPECT_EQ(single->header.frame_id, kFrame);
  expectPositiveDefinite(single->pose.covariance, "~pose/box");

  const auto markers = waitForMessage<visualization_msgs::MarkerArray>(
      kNode + "/markers", kFirstOutputTimeout,
      [](const visualization_msgs::MarkerArray& m) { return !m.markers.empty(); });
  ASSERT_TRUE(markers);
  const bool ellipsoid = std::any_of(
      markers->markers.begin(), markers->markers.end(), [](const visualization_msgs::Marker& m) {
        return m.ns == "uncertainty" && m.type == visualization_msgs::Marker::SPHERE &&
               m.action == visualization_msgs::Marker::ADD;
      });
  EXPECT_TRUE(ellipsoid) << "no uncertainty ellipsoid";
}

TEST(RejectedObjects, AbsentObjectsAreRejectedWithoutTfPoseOrMarker) {
  const auto objects = objectsWithTheBox();
  ASSERT_TRUE(objects) << "no ~objects message with the box";
  for (const std::string& name : kAbsent) {
    for (const ObjectPose& o : objects->objects) EXPECT_NE(o.name, name) << "published a pose";
    const RejectedObject* r = rejected(*objects, name);
    ASSERT_NE(r, nullptr) << name << " is not listed as rejected";
    EXPECT_FALSE(r->reason.empty()) << name;
  }
  EXPECT_LT(rejected(*objects, "noise")->confidence, 0.5);
  // Alone the look-alike fits the box: the box's pose explains its surface.
  EXPECT_NE(rejected(*objects, "lookalike")->reason.find("explained by box 0"), std::string::npos)
      << rejected(*objects, "lookalike")->reason;
  EXPECT_EQ(objects->objects.size(), 1u);

  const auto poses =
      waitForMessage<geometry_msgs::PoseArray>(kNode + "/poses", kFirstOutputTimeout);
  ASSERT_TRUE(poses);
  EXPECT_EQ(poses->poses.size(), 1u) << "only the box has a ~poses entry";

  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  ASSERT_TRUE(buffer.canTransform(kFrame, "box", ros::Time(0), ros::Duration(10)));
  for (const std::string& name : kAbsent) {
    EXPECT_FALSE(buffer.canTransform(kFrame, name, ros::Time(0), ros::Duration(3)))
        << name << " has a TF frame";
  }
  const auto markers = waitForMessage<visualization_msgs::MarkerArray>(
      kNode + "/markers", kFirstOutputTimeout,
      [](const visualization_msgs::MarkerArray& m) { return !m.markers.empty(); });
  ASSERT_TRUE(markers);
  for (const visualization_msgs::Marker& m : markers->markers) {
    if (m.action != visualization_msgs::Marker::ADD) continue;
    EXPECT_TRUE(std::find(kAbsent.begin(), kAbsent.end(), m.ns) == kAbsent.end()) << m.ns;
  }
}

TEST(RejectedObjects, TheServiceNamesTheRejectedObjects) {
  ASSERT_TRUE(objectsWithTheBox()) << "the node never produced a frame";
  const std::string name = kNode + "/estimate";
  ASSERT_TRUE(ros::service::waitForService(name, ros::Duration(kFirstOutputTimeout)));
  Estimate srv;
  ASSERT_TRUE(callService(name, srv)) << name;
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  ASSERT_EQ(srv.response.result.objects.size(), 1u) << srv.response.message;
  EXPECT_EQ(srv.response.result.objects[0].name, "box");
  expectPositiveDefinite(srv.response.result.objects[0].pose.covariance, "~estimate");
  for (const std::string& absent : kAbsent) {
    EXPECT_NE(rejected(srv.response.result, absent), nullptr) << absent;
    EXPECT_NE(srv.response.message.find(absent + " ("), std::string::npos) << srv.response.message;
  }
  const RejectedObject* lookalike = rejected(srv.response.result, "lookalike");
  ASSERT_NE(lookalike, nullptr);
  EXPECT_EQ(lookalike->reason, "explained by box 0");
  EXPECT_NE(srv.response.message.find("; rejected: "), std::string::npos) << srv.response.message;
}

}  // namespace
}  // namespace stocs_ros::test

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_rejected_objects");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
