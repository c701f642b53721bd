// A frame's result as messages: found objects only, their fields, and markers that delete what is
// no longer found.
#include <gtest/gtest.h>

#include "stocs_ros/result_messages.h"

namespace stocs_ros {
namespace {

EstimationSetup twoObjects() {
  EstimationSetup setup;
  for (const char* name : {"box", "can"}) {
    ObjectConfig o;
    o.name = name;
    o.id = static_cast<int>(setup.config.objects.size()) + 5;
    setup.config.objects.push_back(o);
    stocs::PreparedModel m;
    for (int i = 0; i < 5000; ++i) m.model.points.emplace_back(0.001f * i, 0, 0);
    m.model.diameter = 5;
    setup.models.push_back(m);
  }
  setup.config.objects[1].mesh_url = "package://stocs_ros/meshes/can.stl";
  setup.config.objects[1].mesh_scale = 0.001f;
  return setup;
}

ObjectOutcome outcome(size_t object, bool found, float x) {
  ObjectOutcome o{object, {}};
  o.estimate.estimate.found = found;
  o.estimate.estimate.pose.translation() = Eigen::Vector3f(x, 0, 1);
  o.estimate.estimate.lcp.score = 0.25f;
  o.estimate.estimate.hypotheses = 42;
  o.estimate.seconds = 0.5;
  return o;
}

TEST(ResultMessages, OnlyFoundObjectsAreReported) {
  const EstimationSetup setup = twoObjects();
  FrameResult result;
  result.header.frame_id = "camera";
  result.header.stamp = ros::Time(12.5);
  result.objects = {outcome(0, false, 0), outcome(1, true, 0.3f)};
  const ObjectPoseArray objects = toObjectPoseArray(result, setup);
  EXPECT_EQ(objects.header.frame_id, "camera");
  EXPECT_EQ(objects.header.stamp, ros::Time(12.5));
  ASSERT_EQ(objects.objects.size(), 1u);
  EXPECT_EQ(objects.objects[0].name, "can");
  EXPECT_EQ(objects.objects[0].id, 6);
  EXPECT_FLOAT_EQ(objects.objects[0].score, 0.25f);
  EXPECT_EQ(objects.objects[0].estimation_time, 0.5);
  EXPECT_EQ(objects.objects[0].hypotheses_verified, 42);
  EXPECT_FLOAT_EQ(objects.objects[0].pose.position.x, 0.3f);
  EXPECT_EQ(objects.objects[0].pose.orientation.w, 1.0);
  const geometry_msgs::PoseArray poses = toPoseArray(result);
  ASSERT_EQ(poses.poses.size(), 1u);
  EXPECT_EQ(poses.poses[0], objects.objects[0].pose);
}

TEST(ResultMessages, MarkersShowFoundObjectsAndDeleteStaleOnes) {
  const EstimationSetup setup = twoObjects();
  std::set<std::string> shown;
  FrameResult both;
  both.header.frame_id = "camera";
  both.objects = {outcome(0, true, 0.1f), outcome(1, true, 0.2f)};
  const visualization_msgs::MarkerArray first = toMarkers(both, setup, shown);
  ASSERT_EQ(first.markers.size(), 4u);
  EXPECT_EQ(first.markers[0].ns, "box");
  EXPECT_EQ(first.markers[0].type, visualization_msgs::Marker::POINTS);
  EXPECT_LE(first.markers[0].points.size(), 2000u);
  EXPECT_GT(first.markers[0].points.size(), 1000u);
  EXPECT_EQ(first.markers[1].type, visualization_msgs::Marker::TEXT_VIEW_FACING);
  EXPECT_EQ(first.markers[1].text, "box 0.250");
  EXPECT_EQ(first.markers[2].type, visualization_msgs::Marker::MESH_RESOURCE);
  EXPECT_EQ(first.markers[2].mesh_resource, "package://stocs_ros/meshes/can.stl");
  EXPECT_FLOAT_EQ(first.markers[2].scale.x, 0.001f);
  for (const auto& m : first.markers) EXPECT_EQ(m.header.frame_id, "camera");
  EXPECT_EQ(shown, (std::set<std::string>{"box", "can"}));

  FrameResult only_can = both;
  only_can.objects[0].estimate.estimate.found = false;
  const visualization_msgs::MarkerArray second = toMarkers(only_can, setup, shown);
  ASSERT_EQ(second.markers.size(), 4u);
  int deleted = 0;
  for (const auto& m : second.markers) {
    if (m.action == visualization_msgs::Marker::DELETE) {
      EXPECT_EQ(m.ns, "box");
      ++deleted;
    }
  }
  EXPECT_EQ(deleted, 2);
  EXPECT_EQ(shown, (std::set<std::string>{"can"}));
  // Once deleted, a marker is not deleted again.
  EXPECT_EQ(toMarkers(only_can, setup, shown).markers.size(), 2u);
}

}  // namespace
}  // namespace stocs_ros
