// The StoCS node (or nodelet) fed by the scene publisher playing a BOP frame with a known pose:
// TF, ~poses, ~objects and ~markers agree with the ground truth, and so do the publisher's gt_
// frame and ground-truth markers; ~estimate answers on the latest frame and on explicit inputs (a
// cloud, or a depth image with its camera_info) and names bad requests; outputs keep up with the
// input rate without repeated TF stamps. Parameters (private) say which frame and object and how
// close.
#include <cv_bridge/cv_bridge.h>
#include <fmt/format.h>
#include <geometry_msgs/PoseArray.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <stocs_ros/Estimate.h>
#include <stocs_ros/ObjectPoseArray.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <condition_variable>
#include <map>
#include <mutex>
#include <regex>
#include <set>

#include "ros_test_support.h"
#include "test_support.h"

namespace stocs_ros::test {
namespace {

struct Expected {
  std::string dataset;  ///< a path, or a name under STOCS_DATASETS when real_data
  bool real_data = false;
  int scene = 0, image = 0, obj_id = 1;
  std::string object, frame_id, node, cloud_topic, probability_topic;
  std::string depth_topic, camera_info_topic;  ///< empty: no depth image test
  double max_translation = 0.01, max_rotation = 0.1, input_rate = 1.0;
  /// When positive: ADD-S limit as a fraction of the diameter, instead of max_rotation.
  double max_adds = 0;
  bool service_inputs = true;
};
Expected g_expected;

constexpr double kFirstOutputTimeout = 120;  // seconds: includes preparing an uncached model

class NodeOutputs : public ::testing::Test {
 protected:
  void SetUp() override {
    std::filesystem::path dataset = g_expected.dataset;
    if (g_expected.real_data) {
      const std::filesystem::path root = stocs::test::datasetsDir();
      // Set but missing: fail at once rather than wait for outputs that cannot come.
      ASSERT_FALSE(HasFailure());
      if (root.empty()) GTEST_SKIP() << "STOCS_DATASETS is not set; real-data test skipped";
      dataset = root / g_expected.dataset;
    }
    truth_ = groundTruthPose(dataset, g_expected.scene, g_expected.image, g_expected.obj_id);
    dataset_ = dataset;
  }

  void expectNearTruth(const Eigen::Isometry3d& pose, const std::string& what) const {
    EXPECT_LT(translationError(pose, truth_), g_expected.max_translation) << what;
    if (g_expected.max_adds > 0) {
      EXPECT_LT(addsDiameterRatio(dataset_, g_expected.obj_id, pose, truth_), g_expected.max_adds)
          << what << ": ADD-S as a fraction of the diameter";
    } else {
      EXPECT_LT(rotationError(pose, truth_), g_expected.max_rotation) << what;
    }
  }

  static std::optional<ObjectPoseArray> nextObjects(double timeout = kFirstOutputTimeout) {
    return waitForMessage<ObjectPoseArray>(
        g_expected.node + "/objects", timeout,
        [](const ObjectPoseArray& m) { return !m.objects.empty(); });
  }

  static Estimate::Response callEstimate(Estimate::Request request) {
    const std::string name = g_expected.node + "/estimate";
    EXPECT_TRUE(ros::service::waitForService(name, ros::Duration(kFirstOutputTimeout)));
    Estimate srv;
    srv.request = std::move(request);
    EXPECT_TRUE(callService(name, srv)) << name;
    return srv.response;
  }

  /// ~estimate on explicit inputs with the header `input`: one pose, near the truth.
  void expectOnePoseNearTruth(const Estimate::Request& request, const std_msgs::Header& input,
                              const std::string& what) const {
    const Estimate::Response r = callEstimate(request);
    ASSERT_TRUE(r.success) << what << ": " << r.message;
    ASSERT_EQ(r.result.objects.size(), 1u) << what;
    EXPECT_EQ(r.result.header.stamp, input.stamp) << what;
    EXPECT_EQ(r.result.header.frame_id, input.frame_id) << what;
    expectNearTruth(poseToEigen(r.result.objects[0].pose.pose), what);
  }

  static void expectError(Estimate::Request request, const std::string& expected) {
    const Estimate::Response e = callEstimate(std::move(request));
    EXPECT_FALSE(e.success) << "expected an error naming '" << expected << "'";
    EXPECT_NE(e.message.find(expected), std::string::npos) << e.message;
  }

  Eigen::Isometry3d truth_;
  std::filesystem::path dataset_;
};

TEST_F(NodeOutputs, ObjectsMessageIsNearTheGroundTruth) {
  const auto objects = nextObjects();
  ASSERT_TRUE(objects) << "no " << g_expected.node << "/objects message";
  EXPECT_EQ(objects->header.frame_id, g_expected.frame_id);
  ASSERT_EQ(objects->objects.size(), 1u);
  const ObjectPose& o = objects->objects[0];
  EXPECT_EQ(o.name, g_expected.object);
  EXPECT_EQ(o.id, g_expected.obj_id);
  EXPECT_GT(o.score, 0.0);
  EXPECT_GT(o.estimation_time, 0.0);
  // Tracking (the default) scores hypotheses only in a frame it detects in place.
  EXPECT_LE(o.state, ObjectPose::REDETECTED);
  if (o.state == ObjectPose::DETECTED) {
    EXPECT_GT(o.hypotheses_verified, 0);
  } else if (o.state == ObjectPose::TRACKED) {
    EXPECT_EQ(o.hypotheses_verified, 0);
  }
  expectNearTruth(poseToEigen(o.pose.pose), "~objects");
}

TEST_F(NodeOutputs, PoseArrayAndTfGiveTheSamePose) {
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  const auto poses = waitForMessage<geometry_msgs::PoseArray>(
      g_expected.node + "/poses", kFirstOutputTimeout,
      [](const geometry_msgs::PoseArray& m) { return !m.poses.empty(); });
  ASSERT_TRUE(poses);
  ASSERT_EQ(poses->poses.size(), 1u);
  EXPECT_EQ(poses->header.frame_id, g_expected.frame_id);
  expectNearTruth(poseToEigen(poses->poses[0]), "~poses");

  // TF from the cloud's frame to the object, stamped with the cloud's stamp.
  const geometry_msgs::TransformStamped t = buffer.lookupTransform(
      g_expected.frame_id, g_expected.object, poses->header.stamp, ros::Duration(10));
  EXPECT_EQ(t.header.stamp, poses->header.stamp);
  const Eigen::Isometry3d tf_pose = tf2::transformToEigen(t);
  EXPECT_LT(translationError(tf_pose, poseToEigen(poses->poses[0])), 1e-6);
  EXPECT_LT(rotationError(tf_pose, poseToEigen(poses->poses[0])), 1e-4);
  expectNearTruth(tf_pose, "TF");
}

TEST_F(NodeOutputs, PublisherGroundTruthFrameMatchesTheDataset) {
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  const Eigen::Isometry3d gt = tf2::transformToEigen(buffer.lookupTransform(
      g_expected.frame_id, "gt_" + g_expected.object, ros::Time(0), ros::Duration(30)));
  EXPECT_LT(translationError(gt, truth_), 1e-6);
  EXPECT_LT(rotationError(gt, truth_), 1e-3);
}

TEST_F(NodeOutputs, PublisherGroundTruthMarkersDrawTheDatasetsTruthWithTheFramesStamp) {
  // The markers and the gt_ TF frames of the played frames, matched by stamp.
  const std::string ns = "gt_" + g_expected.object;
  std::mutex mutex;
  std::condition_variable arrived;
  std::set<ros::Time> tf_stamps;
  std::map<ros::Time, visualization_msgs::Marker> bodies;  // by stamp
  ros::NodeHandle nh;
  const boost::function<void(const tf2_msgs::TFMessage::ConstPtr&)> on_tf =
      [&](const tf2_msgs::TFMessage::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto& t : m->transforms) {
          if (t.child_frame_id == ns) tf_stamps.insert(t.header.stamp);
        }
        arrived.notify_all();
      };
  const boost::function<void(const visualization_msgs::MarkerArray::ConstPtr&)> on_markers =
      [&](const visualization_msgs::MarkerArray::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        for (const visualization_msgs::Marker& marker : m->markers) {
          if (marker.ns == ns && marker.action == visualization_msgs::Marker::ADD) {
            bodies[marker.header.stamp] = marker;
          }
        }
        arrived.notify_all();
      };
  ros::Subscriber tf_sub = nh.subscribe<tf2_msgs::TFMessage>("/tf", 100, on_tf);
  ros::Subscriber markers_sub = nh.subscribe<visualization_msgs::MarkerArray>(
      "/scene_publisher/ground_truth_markers", 5, on_markers);
  std::unique_lock<std::mutex> lock(mutex);
  const auto same_frame = [&]() -> const visualization_msgs::Marker* {
    for (const auto& [stamp, marker] : bodies) {
      if (tf_stamps.count(stamp)) return &marker;
    }
    return nullptr;
  };
  arrived.wait_for(lock, std::chrono::seconds(30), [&] { return same_frame() != nullptr; });
  ASSERT_FALSE(bodies.empty()) << "no " << ns << " marker on /scene_publisher/ground_truth_markers";
  const visualization_msgs::Marker* body = same_frame();
  ASSERT_TRUE(body) << "no " << ns << " marker has the stamp of a " << ns << " TF frame";
  EXPECT_EQ(body->header.frame_id, g_expected.frame_id);
  EXPECT_EQ(body->id, 0);
  EXPECT_TRUE(body->type == visualization_msgs::Marker::POINTS ||
              body->type == visualization_msgs::Marker::MESH_RESOURCE);
  EXPECT_LT(translationError(poseToEigen(body->pose), truth_), 1e-6);
  EXPECT_LT(rotationError(poseToEigen(body->pose), truth_), 1e-3);
}

TEST_F(NodeOutputs, MarkersShowTheObjectWithALabel) {
  const auto markers = waitForMessage<visualization_msgs::MarkerArray>(
      g_expected.node + "/markers", kFirstOutputTimeout,
      [](const visualization_msgs::MarkerArray& m) { return !m.markers.empty(); });
  ASSERT_TRUE(markers);
  bool body = false, label = false;
  for (const visualization_msgs::Marker& m : markers->markers) {
    if (m.ns != g_expected.object || m.action != visualization_msgs::Marker::ADD) continue;
    EXPECT_EQ(m.header.frame_id, g_expected.frame_id);
    if (m.id == 0) {
      body = true;
      EXPECT_TRUE(m.type == visualization_msgs::Marker::POINTS ||
                  m.type == visualization_msgs::Marker::MESH_RESOURCE);
      expectNearTruth(poseToEigen(m.pose), "body marker");
    } else if (m.id == 1) {
      label = true;
      EXPECT_EQ(m.type, visualization_msgs::Marker::TEXT_VIEW_FACING);
      // "name confidence": a probability with two decimals (the score had three).
      EXPECT_TRUE(
          std::regex_match(m.text, std::regex(g_expected.object + " (0\\.[0-9]{2}|1\\.00)")))
          << m.text;
    }
  }
  EXPECT_TRUE(body);
  EXPECT_TRUE(label);
}

TEST_F(NodeOutputs, ServiceEstimatesTheLatestFrameAndRejectsUnknownObjects) {
  ASSERT_TRUE(nextObjects()) << "the node never produced a frame";
  Estimate::Request all;
  all.time_budget = 5.0;
  const Estimate::Response r = callEstimate(all);
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_EQ(r.message, "1 of 1 objects found");
  EXPECT_EQ(r.result.header.frame_id, g_expected.frame_id);
  ASSERT_EQ(r.result.objects.size(), 1u);
  EXPECT_EQ(r.result.objects[0].name, g_expected.object);
  expectNearTruth(poseToEigen(r.result.objects[0].pose.pose), "~estimate");

  Estimate::Request unknown;
  unknown.objects = {"no_such_object"};
  const Estimate::Response u = callEstimate(unknown);
  EXPECT_FALSE(u.success);
  EXPECT_NE(u.message.find("unknown object 'no_such_object'"), std::string::npos) << u.message;
  EXPECT_TRUE(u.result.objects.empty());

  Estimate::Request negative;
  negative.time_budget = -1;
  const Estimate::Response n = callEstimate(negative);
  EXPECT_FALSE(n.success);
  EXPECT_NE(n.message.find("negative"), std::string::npos) << n.message;
}

TEST_F(NodeOutputs, ServiceEstimatesExplicitInputsAndNamesBadOnes) {
  if (!g_expected.service_inputs) GTEST_SKIP() << "the played frame has no per-object image topic";
  const auto cloud = waitForMessage<sensor_msgs::PointCloud2>(g_expected.cloud_topic, 30);
  const auto probability = waitForMessage<sensor_msgs::Image>(g_expected.probability_topic, 30);
  ASSERT_TRUE(cloud && probability)
      << g_expected.cloud_topic << ", " << g_expected.probability_topic;

  Estimate::Request good;
  good.objects = {g_expected.object};
  good.cloud = *cloud;
  good.probabilities = {*probability};
  expectOnePoseNearTruth(good, cloud->header, "~estimate on explicit inputs");

  Estimate::Request colour = good;
  colour.probabilities[0].encoding = "rgb8";
  expectError(colour, "encoding 'rgb8'");

  Estimate::Request small = good;
  small.probabilities[0] =
      *cv_bridge::CvImage(probability->header, "mono8", cv::Mat(10, 10, CV_8UC1, cv::Scalar(255)))
           .toImageMsg();
  expectError(small, "probability image is 10x10 but the cloud is");

  Estimate::Request two = good;
  two.probabilities.push_back(*probability);
  expectError(two, "2 probability images for 1 objects");

  Estimate::Request empty_cloud = good;
  empty_cloud.cloud.data.clear();
  empty_cloud.cloud.width = 1;
  empty_cloud.cloud.height = 0;
  expectError(empty_cloud, "cloud: cloud is empty");
}

TEST_F(NodeOutputs, ServiceEstimatesAnExplicitDepthImageAndNamesBadOnes) {
  if (!g_expected.service_inputs || g_expected.depth_topic.empty()) {
    GTEST_SKIP() << "no depth image and per-object image topics given";
  }
  // The publisher plays one frame in a loop: messages of different stamps hold the same images.
  const auto depth = waitForMessage<sensor_msgs::Image>(g_expected.depth_topic, 30);
  const auto info = waitForMessage<sensor_msgs::CameraInfo>(g_expected.camera_info_topic, 30);
  const auto probability = waitForMessage<sensor_msgs::Image>(g_expected.probability_topic, 30);
  const auto cloud = waitForMessage<sensor_msgs::PointCloud2>(g_expected.cloud_topic, 30);
  ASSERT_TRUE(depth && info && probability && cloud);

  Estimate::Request good;
  good.objects = {g_expected.object};
  good.depth = *depth;
  good.camera_info = *info;
  good.probabilities = {*probability};
  expectOnePoseNearTruth(good, depth->header, "~estimate on a depth image");

  Estimate::Request both = good;
  both.cloud = *cloud;
  expectError(both, "both a cloud and a depth image were given");
  Estimate::Request no_info = good;
  no_info.camera_info = sensor_msgs::CameraInfo();
  expectError(no_info, "a depth image was given without its camera_info");
  Estimate::Request with_cloud = good;
  with_cloud.depth = sensor_msgs::Image();
  with_cloud.cloud = *cloud;
  expectError(with_cloud, "a camera_info was given without a depth image");
  Estimate::Request narrow = good;
  narrow.camera_info.width /= 2;
  expectError(narrow, fmt::format("depth image: depth image is {}x{} but the camera is {}x{}",
                                  depth->width, depth->height, depth->width / 2, depth->height));
  Estimate::Request colour = good;
  colour.depth.encoding = "rgb8";
  expectError(colour,
              "depth image: depth image has encoding 'rgb8'; REP 118 depth is 16UC1 (mm) or 32FC1 "
              "(m)");
  Estimate::Request info_only;
  info_only.camera_info = *info;
  expectError(info_only, "a camera_info was given without a depth image");
  Estimate::Request probabilities_only;
  probabilities_only.probabilities = {*probability};
  expectError(probabilities_only, "probabilities were given without a cloud or depth image");
}

TEST_F(NodeOutputs, OutputsKeepUpWithTheInputWithoutRepeatedTfStamps) {
  ASSERT_TRUE(nextObjects()) << "the node never produced a frame";
  std::mutex mutex;
  std::vector<double> latencies, estimation_times;
  std::map<std::string, std::vector<ros::Time>> tf_stamps;
  ros::NodeHandle nh;
  const boost::function<void(const ObjectPoseArray::ConstPtr&)> on_objects =
      [&](const ObjectPoseArray::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        latencies.push_back((ros::Time::now() - m->header.stamp).toSec());
        for (const ObjectPose& o : m->objects) estimation_times.push_back(o.estimation_time);
      };
  const boost::function<void(const tf2_msgs::TFMessage::ConstPtr&)> on_tf =
      [&](const tf2_msgs::TFMessage::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto& t : m->transforms) tf_stamps[t.child_frame_id].push_back(t.header.stamp);
      };
  ros::Subscriber objects_sub =
      nh.subscribe<ObjectPoseArray>(g_expected.node + "/objects", 10, on_objects);
  ros::Subscriber tf_sub = nh.subscribe<tf2_msgs::TFMessage>("/tf", 100, on_tf);
  const double window = 10.0;
  ros::WallDuration(window / 2).sleep();
  // Estimating the latest frame again must not send its TF a second time.
  EXPECT_TRUE(callEstimate({}).success);
  ros::WallDuration(window / 2).sleep();
  objects_sub.shutdown();
  tf_sub.shutdown();

  std::lock_guard<std::mutex> lock(mutex);
  // The node keeps pace with whichever is slower, the input or its own estimation (measured here,
  // so that a loaded machine does not fail the test), and never builds a backlog of old frames.
  ASSERT_FALSE(estimation_times.empty()) << "no ~objects message in " << window << " s";
  const double estimation = *std::max_element(estimation_times.begin(), estimation_times.end());
  const double period = std::max(1.0 / g_expected.input_rate, estimation);
  EXPECT_GE(latencies.size(), 0.5 * window / period)
      << latencies.size() << " ~objects messages in " << window << " s; input every "
      << 1.0 / g_expected.input_rate << " s, estimation up to " << estimation << " s";
  const double latency = *std::max_element(latencies.begin(), latencies.end());
  // Worst case: the frame waits for an estimation and a service call, then is estimated itself.
  EXPECT_LT(latency, 1.0 / g_expected.input_rate + 3 * estimation + 0.5)
      << "an output came " << latency << " s after its frame";
  const std::vector<ros::Time>& stamps = tf_stamps[g_expected.object];
  EXPECT_GE(stamps.size(), 2u);
  for (size_t i = 1; i < stamps.size(); ++i) {
    EXPECT_LT(stamps[i - 1], stamps[i])
        << "TF of " << g_expected.object << " repeated or went back";
  }
}

}  // namespace
}  // namespace stocs_ros::test

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_node_outputs");
  ros::NodeHandle pnh("~");
  stocs_ros::test::Expected& e = stocs_ros::test::g_expected;
  pnh.getParam("dataset", e.dataset);
  pnh.getParam("real_data", e.real_data);
  pnh.getParam("scene", e.scene);
  pnh.getParam("image", e.image);
  pnh.getParam("obj_id", e.obj_id);
  pnh.getParam("object", e.object);
  pnh.getParam("frame_id", e.frame_id);
  pnh.getParam("node", e.node);
  pnh.getParam("cloud_topic", e.cloud_topic);
  pnh.getParam("probability_topic", e.probability_topic);
  pnh.getParam("depth_topic", e.depth_topic);
  pnh.getParam("camera_info_topic", e.camera_info_topic);
  pnh.getParam("max_translation", e.max_translation);
  pnh.getParam("max_rotation", e.max_rotation);
  pnh.getParam("max_adds", e.max_adds);
  pnh.getParam("input_rate", e.input_rate);
  pnh.getParam("service_inputs", e.service_inputs);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
