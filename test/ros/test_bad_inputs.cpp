// The node fed bad messages directly (remapped to /bad/cloud and /bad/probability/box): wrong
// encoding, size mismatch, all-NaN, empty and unorganized clouds, stamps that never match. None
// may produce an output or stop the node; each is counted on ~statistics under the input at fault;
// the service names the latest frame's problem; a good frame afterwards is estimated near the
// ground truth; concurrent service calls are all answered; frames played again with the same
// stamps, as a bag loop plays them, are estimated and published again.
#include <cv_bridge/cv_bridge.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_srvs/Trigger.h>
#include <stocs_ros/Estimate.h>
#include <stocs_ros/ObjectPoseArray.h>
#include <tf2_eigen/tf2_eigen.h>

#include <cstring>
#include <fstream>
#include <future>
#include <iterator>
#include <limits>
#include <map>
#include <mutex>
#include <opencv2/core.hpp>
#include <set>

#include "ros_test_support.h"

namespace stocs_ros::test {
namespace {

std::filesystem::path g_dataset;
std::filesystem::path g_config;  ///< the node's configuration file, rewritten by the reload test
constexpr char kService[] = "/stocs/estimate";

class BadInputs : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ros::NodeHandle nh;
    cloud_pub_ = nh.advertise<sensor_msgs::PointCloud2>("/bad/cloud", 5);
    probability_pub_ = nh.advertise<sensor_msgs::Image>("/bad/probability/box", 5);
    const InputFrame frame = loadInputFrame(g_dataset);
    good_cloud_ = frame.cloud;
    good_probability_ = frame.probability;
    const boost::function<void(const ObjectPoseArray::ConstPtr&)> on_objects =
        [](const ObjectPoseArray::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex_);
          output_stamps_.insert(m->header.stamp);  // once per output
          last_output_ = *m;
        };
    objects_sub_ = nh.subscribe<ObjectPoseArray>("/stocs/objects", 10, on_objects);
    // The node subscribes once its model is ready.
    const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(120);
    while ((cloud_pub_.getNumSubscribers() == 0 || probability_pub_.getNumSubscribers() == 0) &&
           ros::WallTime::now() < until) {
      ros::WallDuration(0.1).sleep();
    }
  }

  static void TearDownTestSuite() {
    objects_sub_.shutdown();
    cloud_pub_.shutdown();
    probability_pub_.shutdown();
  }

  /// Publishes a frame with stamps `cloud_stamp` and `probability_stamp`.
  static void publish(sensor_msgs::PointCloud2 cloud, sensor_msgs::Image probability,
                      const ros::Time& cloud_stamp, const ros::Time& probability_stamp) {
    cloud.header.stamp = cloud_stamp;
    probability.header.stamp = probability_stamp;
    cloud_pub_.publish(cloud);
    probability_pub_.publish(probability);
  }

  static ros::Time publishBad(sensor_msgs::PointCloud2 cloud, sensor_msgs::Image probability) {
    const ros::Time stamp = ros::Time::now();
    publish(std::move(cloud), std::move(probability), stamp, stamp);
    bad_stamps_.push_back(stamp);
    ros::WallDuration(0.5).sleep();
    return stamp;
  }

  /// Waits up to a minute for the `n`-th output stamped `stamp`.
  static bool waitForOutputs(const ros::Time& stamp, size_t n) {
    const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(60);
    while (ros::WallTime::now() < until) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (output_stamps_.count(stamp) >= n) return true;
      }
      ros::WallDuration(0.1).sleep();
    }
    return false;
  }

  static Estimate::Response estimate() {
    EXPECT_TRUE(ros::service::waitForService(kService, ros::Duration(60)));
    Estimate srv;
    EXPECT_TRUE(callService(kService, srv));
    return srv.response;
  }

  static ros::Publisher cloud_pub_, probability_pub_;
  static ros::Subscriber objects_sub_;
  static sensor_msgs::PointCloud2 good_cloud_;
  static sensor_msgs::Image good_probability_;
  static std::vector<ros::Time> bad_stamps_;
  static std::mutex mutex_;
  static std::multiset<ros::Time> output_stamps_;
  static ObjectPoseArray last_output_;
};

ros::Publisher BadInputs::cloud_pub_, BadInputs::probability_pub_;
ros::Subscriber BadInputs::objects_sub_;
sensor_msgs::PointCloud2 BadInputs::good_cloud_;
sensor_msgs::Image BadInputs::good_probability_;
std::vector<ros::Time> BadInputs::bad_stamps_;
std::mutex BadInputs::mutex_;
std::multiset<ros::Time> BadInputs::output_stamps_;
ObjectPoseArray BadInputs::last_output_;

/// The latest ~statistics counters by key (the topic is latched), once `ready` holds for them.
std::map<std::string, uint64_t> statistics(
    const std::function<bool(std::map<std::string, uint64_t>&)>& ready) {
  std::map<std::string, uint64_t> counts;
  waitForMessage<diagnostic_msgs::DiagnosticArray>("/stocs/statistics", 10,
                                                   [&](const diagnostic_msgs::DiagnosticArray& m) {
                                                     counts = statisticsCounts(m);
                                                     return ready(counts);
                                                   });
  return counts;
}

/// The five bad frames were matched and rejected, counted by the input their error names; the
/// frame whose stamps never matched is dropped or still waiting, never lost.
void expectCountedByInputAtFault() {
  std::map<std::string, uint64_t> c = statistics([](auto& c) { return c["frames rejected"] >= 5; });
  EXPECT_EQ(c["frames rejected"], 5u);
  EXPECT_EQ(c["frames rejected: probability image of 'box'"], 1u);  // rgb8
  EXPECT_EQ(c["frames rejected: object 'box'"], 1u);                // 10x10 probability image
  EXPECT_EQ(c["frames rejected: cloud"], 3u);                       // NaN, empty, unorganized
  EXPECT_EQ(c["frames estimated"], 0u);
  EXPECT_EQ(c["frames matched"], 5u);
  for (const std::string topic : {"/bad/cloud", "/bad/probability/box"}) {
    EXPECT_EQ(c["received " + topic], 6u) << topic;
    EXPECT_EQ(c["received " + topic],
              c["frames matched"] + droppedMessages(c, topic) + c["queued " + topic])
        << topic;
  }
}

TEST_F(BadInputs, ServiceBeforeAnyFrameSaysThereIsNone) {
  ASSERT_GT(cloud_pub_.getNumSubscribers(), 0u) << "the node never subscribed /bad/cloud";
  const Estimate::Response r = estimate();
  EXPECT_FALSE(r.success);
  EXPECT_NE(r.message.find("no synchronized input frame yet"), std::string::npos) << r.message;
}

TEST_F(BadInputs, BadFramesGiveNoOutputAndTheNodeKeepsAnswering) {
  sensor_msgs::Image colour = good_probability_;
  colour.encoding = "rgb8";
  publishBad(good_cloud_, colour);

  sensor_msgs::Image small = *cv_bridge::CvImage(good_probability_.header, "mono8",
                                                 cv::Mat(10, 10, CV_8UC1, cv::Scalar(200)))
                                  .toImageMsg();
  publishBad(good_cloud_, small);

  sensor_msgs::PointCloud2 nan_cloud = good_cloud_;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (size_t i = 0; i + sizeof(float) <= nan_cloud.data.size(); i += sizeof(float)) {
    std::memcpy(&nan_cloud.data[i], &nan, sizeof(float));
  }
  publishBad(nan_cloud, good_probability_);

  sensor_msgs::PointCloud2 empty_cloud = good_cloud_;
  empty_cloud.width = empty_cloud.height = 0;
  empty_cloud.data.clear();
  publishBad(empty_cloud, good_probability_);

  sensor_msgs::PointCloud2 unorganized = good_cloud_;
  unorganized.width *= unorganized.height;
  unorganized.height = 1;
  unorganized.row_step = unorganized.width * unorganized.point_step;
  publishBad(unorganized, good_probability_);

  // Stamps half a second apart never match (tolerance 0.01 s).
  const ros::Time apart = ros::Time::now();
  publish(good_cloud_, good_probability_, apart, apart + ros::Duration(0.5));
  bad_stamps_.push_back(apart);
  ros::WallDuration(2.0).sleep();

  EXPECT_TRUE(ros::service::exists(kService, false)) << "the node is gone";
  // The latest synchronized frame is the unorganized cloud: the service names its problem.
  const Estimate::Response r = estimate();
  EXPECT_FALSE(r.success);
  EXPECT_NE(r.message.find("cloud: cloud is not organized"), std::string::npos) << r.message;
  expectCountedByInputAtFault();
  std::lock_guard<std::mutex> lock(mutex_);
  for (const ros::Time& stamp : bad_stamps_) {
    EXPECT_EQ(output_stamps_.count(stamp), 0u) << "an output for the bad frame at " << stamp;
  }
}

/// Rewrites the node's configuration file and calls ~reload.
std_srvs::Trigger::Response reloadWith(const std::string& config) {
  std::ofstream(g_config) << config;
  std_srvs::Trigger srv;
  EXPECT_TRUE(callService("/stocs/reload", srv));
  return srv.response;
}

/// Puts a file's text back when it goes out of scope, whatever the test did to it.
struct RestoreFile {
  std::filesystem::path file;
  std::string text;
  ~RestoreFile() { std::ofstream(file) << text; }
};

TEST_F(BadInputs, ReloadAppliesAGoodFileAndKeepsTheSetupOnABadOne) {
  std::ifstream file(g_config);
  const RestoreFile restore{g_config, std::string(std::istreambuf_iterator<char>(file), {})};
  const std::string& original = restore.text;
  ASSERT_FALSE(original.empty()) << g_config;

  std_srvs::Trigger::Response r = reloadWith(original + "estimation: {stocs: {bases: 0}}\n");
  EXPECT_FALSE(r.success);
  EXPECT_NE(r.message.find("estimation.stocs.bases: 0 is outside"), std::string::npos) << r.message;
  r = reloadWith(original + "input: {uint16_scale: 100}\n");
  EXPECT_FALSE(r.success);
  EXPECT_NE(r.message.find("restart the node"), std::string::npos) << r.message;
  // The next test estimates a good frame with the reloaded setup.
  r = reloadWith(original + "estimation: {stocs: {bases: 60}}\n");
  EXPECT_TRUE(r.success) << r.message;
  EXPECT_NE(r.message.find("reloaded 1 objects"), std::string::npos) << r.message;
}

TEST_F(BadInputs, AGoodFrameAfterwardsIsEstimated) {
  const ros::Time stamp = ros::Time::now();
  publish(good_cloud_, good_probability_, stamp, stamp);
  ASSERT_TRUE(waitForOutputs(stamp, 1)) << "no output for the good frame";
  ObjectPoseArray output;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    output = last_output_;
  }
  ASSERT_EQ(output.header.stamp, stamp);
  ASSERT_EQ(output.objects.size(), 1u);
  Eigen::Isometry3d pose;
  tf2::fromMsg(output.objects[0].pose.pose, pose);
  const Eigen::Isometry3d truth = groundTruthPose(g_dataset, 0, 0, 1);
  EXPECT_LT(translationError(pose, truth), 0.005);
  EXPECT_LT(rotationError(pose, truth), 0.05);

  const Estimate::Response r = estimate();
  EXPECT_TRUE(r.success) << r.message;
  EXPECT_EQ(r.result.header.stamp, stamp);
}

TEST_F(BadInputs, ConcurrentServiceCallsAreAllAnswered) {
  // Four estimates (one naming an unknown object) and a reload at once: each gets its own answer.
  std::ifstream file(g_config);
  const std::string config(std::istreambuf_iterator<char>(file), {});
  const auto call = [](std::vector<std::string> objects) {
    Estimate srv;
    srv.request.objects = std::move(objects);
    EXPECT_TRUE(callService(kService, srv));
    return srv.response;
  };
  std::vector<std::future<Estimate::Response>> estimates;
  for (int k = 0; k < 3; ++k)
    estimates.push_back(std::async(std::launch::async, call, std::vector<std::string>{"box"}));
  estimates.push_back(std::async(std::launch::async, call, std::vector<std::string>{"ghost"}));
  const std_srvs::Trigger::Response reloaded = reloadWith(config);
  EXPECT_TRUE(reloaded.success) << reloaded.message;
  std::vector<Estimate::Response> r;
  for (auto& f : estimates) r.push_back(f.get());
  for (int k = 0; k < 3; ++k) {
    EXPECT_TRUE(r[k].success) << r[k].message;
    EXPECT_EQ(r[k].message, "1 of 1 objects found");
    EXPECT_EQ(r[k].result.header.stamp, r[0].result.header.stamp);
  }
  EXPECT_FALSE(r[3].success);
  EXPECT_EQ(r[3].message, "unknown object 'ghost'; configured objects: box");
  const std::map<std::string, uint64_t> c =
      statistics([](auto& c) { return c["service calls"] >= 4; });
  EXPECT_GE(c.at("service calls failed"), 1u);
}

TEST_F(BadInputs, FramesPlayedAgainWithTheSameStampsArePublishedAgain) {
  // The first pass of a two-frame bag.
  const ros::Time first = ros::Time::now();
  const ros::Time second = first + ros::Duration(0.5);
  publish(good_cloud_, good_probability_, first, first);
  ASSERT_TRUE(waitForOutputs(first, 1)) << "no output for the first frame";
  publish(good_cloud_, good_probability_, second, second);
  ASSERT_TRUE(waitForOutputs(second, 1)) << "no output for the second frame";
  // The second pass, as `rosbag play -l` plays it: the first frame's stamps again, and the image
  // may come before the cloud. Its output goes back in time and must be published all the same.
  sensor_msgs::PointCloud2 cloud = good_cloud_;
  sensor_msgs::Image probability = good_probability_;
  cloud.header.stamp = probability.header.stamp = first;
  probability_pub_.publish(probability);
  ros::WallDuration(0.2).sleep();
  cloud_pub_.publish(cloud);
  EXPECT_TRUE(waitForOutputs(first, 2)) << "the second pass gave no output";
  const std::map<std::string, uint64_t> c =
      statistics([](auto& c) { return c["time jumps back"] >= 1; });
  EXPECT_EQ(c.at("time jumps back"), 1u);
}

}  // namespace
}  // namespace stocs_ros::test

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_bad_inputs");
  std::string dataset;
  ros::NodeHandle("~").getParam("dataset", dataset);
  stocs_ros::test::g_dataset = dataset;
  std::string config;
  ros::NodeHandle("~").getParam("config", config);
  stocs_ros::test::g_config = config;
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
