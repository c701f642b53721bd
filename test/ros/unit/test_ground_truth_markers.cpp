// The scene publisher's ground-truth markers: each configured truth instance at its pose, in the
// gt_<object> namespace with id k, drawn from the node's model (mesh, or the model samples the node
// would prepare), in one colour of their own; unknown objects skipped, gone instances deleted.
#include <gtest/gtest.h>
#include <tf2_eigen/tf2_eigen.h>

#include <filesystem>
#include <fstream>

#include "stocs/io/mesh_io.h"
#include "stocs_ros/scene_publisher/ground_truth_markers.h"

namespace stocs_ros {
namespace {

/// A 10 cm cube as an ASCII PLY mesh in mm, in the test's temporary folder.
std::filesystem::path writeCube() {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "stocs_gt_cube.ply";
  std::ofstream out(path);
  out << "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
         "property float z\nelement face 12\nproperty list uchar int vertex_indices\nend_header\n";
  for (int i = 0; i < 8; ++i) {
    out << (i & 1 ? 50 : -50) << ' ' << (i & 2 ? 50 : -50) << ' ' << (i & 4 ? 50 : -50) << '\n';
  }
  const int faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                            {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& f : faces) out << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
  return path;
}

NodeConfig twoObjects() {
  NodeConfig config;
  ObjectConfig cube;
  cube.name = "cube";
  cube.model = writeCube();
  config.objects.push_back(cube);
  ObjectConfig can = cube;
  can.name = "can";
  can.mesh_url = "package://stocs_ros/meshes/can.stl";
  can.mesh_scale = 0.001f;
  config.objects.push_back(can);
  return config;
}

Eigen::Isometry3d poseAt(double x, double angle) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(angle, Eigen::Vector3d(0.3, 1, 0.2).normalized()).matrix();
  pose.translation() = Eigen::Vector3d(x, -0.05, 0.9);
  return pose;
}

std_msgs::Header frameHeader() {
  std_msgs::Header header;
  header.frame_id = "camera_optical_frame";
  header.stamp = ros::Time(42.5);
  return header;
}

void expectPose(const visualization_msgs::Marker& m, const Eigen::Isometry3d& expected) {
  Eigen::Isometry3d pose;
  tf2::fromMsg(m.pose, pose);
  EXPECT_LT((pose.translation() - expected.translation()).norm(), 1e-9) << m.ns << " " << m.id;
  EXPECT_TRUE(pose.linear().isApprox(expected.linear(), 1e-9)) << m.ns << " " << m.id;
}

TEST(GroundTruthMarkers, EachTruthInstanceIsDrawnAtItsPoseInItsNamespace) {
  const NodeConfig config = twoObjects();
  GroundTruthMarkers builder(config);
  const std::vector<TruthPose> truth = {{"cube", 0, poseAt(-0.1, 0.4)},
                                        {"cube", 1, poseAt(0.1, 1.2)},
                                        {"can", 0, poseAt(0.0, 2.0)},
                                        {"obj_9", 0, poseAt(0.2, 0.0)}};
  const visualization_msgs::MarkerArray out = builder.build(truth, frameHeader());
  ASSERT_EQ(out.markers.size(), 3u) << "obj_9 is not configured and has no model to draw";
  const std::vector<std::pair<std::string, int>> keys = {
      {"gt_cube", 0}, {"gt_cube", 1}, {"gt_can", 0}};
  for (size_t i = 0; i < keys.size(); ++i) {
    const visualization_msgs::Marker& m = out.markers[i];
    EXPECT_EQ(m.ns, keys[i].first);
    EXPECT_EQ(m.id, keys[i].second);
    EXPECT_EQ(m.action, visualization_msgs::Marker::ADD);
    EXPECT_EQ(m.header.frame_id, "camera_optical_frame");
    EXPECT_EQ(m.header.stamp, ros::Time(42.5));
    expectPose(m, truth[i].pose);
    // Translucent green, unlike the node's opaque per-object colours.
    EXPECT_GT(m.color.g, 2 * std::max(m.color.r, m.color.b));
    EXPECT_LT(m.color.a, 0.6f);
  }
  EXPECT_EQ(out.markers[2].type, visualization_msgs::Marker::MESH_RESOURCE);
  EXPECT_EQ(out.markers[2].mesh_resource, "package://stocs_ros/meshes/can.stl");
  EXPECT_FLOAT_EQ(out.markers[2].scale.x, 0.001f);

  // Without a mesh, the samples the node prepares from the same file and parameters.
  const stocs::ObjectModel node_model = stocs::prepareModel(
      stocs::loadMesh(config.objects[0].model.string(), 0.001f), config.estimation.model.sampling);
  const visualization_msgs::Marker& cube = out.markers[0];
  EXPECT_EQ(cube.type, visualization_msgs::Marker::POINTS);
  ASSERT_EQ(cube.points.size(), node_model.size());
  for (size_t i = 0; i < cube.points.size(); ++i) {
    EXPECT_FLOAT_EQ(cube.points[i].x, node_model.points[i].x());
    EXPECT_FLOAT_EQ(cube.points[i].z, node_model.points[i].z());
  }
}

TEST(GroundTruthMarkers, InstancesNoLongerInTheFrameAreDeleted) {
  const NodeConfig config = twoObjects();
  GroundTruthMarkers builder(config);
  builder.build({{"cube", 0, poseAt(0, 0)}, {"cube", 1, poseAt(0.1, 0)}, {"can", 0, poseAt(0, 1)}},
                frameHeader());
  const visualization_msgs::MarkerArray next =
      builder.build({{"cube", 0, poseAt(0.05, 0)}}, frameHeader());
  std::set<MarkerKey> added, deleted;
  for (const visualization_msgs::Marker& m : next.markers) {
    EXPECT_EQ(m.header.frame_id, "camera_optical_frame");
    (m.action == visualization_msgs::Marker::DELETE ? deleted : added).insert({m.ns, m.id});
  }
  EXPECT_EQ(added, (std::set<MarkerKey>{{"gt_cube", 0}}));
  EXPECT_EQ(deleted, (std::set<MarkerKey>{{"gt_cube", 1}, {"gt_can", 0}}));
  EXPECT_EQ(builder.build({{"cube", 0, poseAt(0.05, 0)}}, frameHeader()).markers.size(), 1u);
}

TEST(GroundTruthMarkers, AnUnreadableModelDrawsNothingAndThrowsNothing) {
  NodeConfig config = twoObjects();
  config.objects[0].model = "/nonexistent/cube.ply";
  GroundTruthMarkers builder(config);
  const visualization_msgs::MarkerArray out =
      builder.build({{"cube", 0, poseAt(0, 0)}, {"can", 0, poseAt(0, 1)}}, frameHeader());
  ASSERT_EQ(out.markers.size(), 1u);
  EXPECT_EQ(out.markers[0].ns, "gt_can");
}

}  // namespace
}  // namespace stocs_ros
