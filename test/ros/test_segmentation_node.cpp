// The segmentation node or nodelet (test/ros/segmentation_node.test): it subscribes to the colour
// image only while its output has a subscriber, answers a colour image with a 32FC6 (or, with
// ~probability_depth 8U, 8UC6) probability image of the same header and size holding the
// network's maps for the six objects, and counts an image of a wrong encoding without stopping.
#include <cv_bridge/cv_bridge.h>
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <functional>
#include <mutex>
#include <opencv2/imgcodecs.hpp>

#include "ros_test_support.h"
#include "stocs/segmentation/segmentation_network.h"

namespace stocs_ros::test {
namespace {

std::string g_rgb;            ///< the generated scene's colour image
std::string g_depth = "32F";  ///< the node's ~probability_depth

/// Whether `done` became true within `timeout` seconds.
bool waitUntil(const std::function<bool()>& done, double timeout) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
  while (!done()) {
    if (ros::WallTime::now() > end) return false;
    ros::WallDuration(0.05).sleep();
  }
  return true;
}

sensor_msgs::ImagePtr imageMessage(const cv::Mat& image, const std::string& encoding, int secs) {
  std_msgs::Header header;
  header.stamp = ros::Time(secs, 5);
  header.frame_id = "camera_optical_frame";
  return cv_bridge::CvImage(header, encoding, image).toImageMsg();
}

/// The published maps hold the package network's maps of channels 1 to 6 (the objects), as
/// probabilities or as round(255 p).
void expectNetworksMaps(const sensor_msgs::Image& msg, const cv::Mat& bgr) {
  stocs::SegmentationNetworkParams params;
  params.model = SEGMENTER_MODEL;
  const std::vector<cv::Mat> expected = stocs::SegmentationNetwork(params).segment(bgr);
  const bool bytes = g_depth == "8U";
  const cv::Mat image = cv_bridge::toCvCopy(msg)->image;
  std::vector<cv::Mat> channels;
  cv::split(image, channels);
  ASSERT_EQ(channels.size(), 6u);
  for (size_t c = 0; c < channels.size(); ++c) {
    cv::Mat p;
    channels[c].convertTo(p, CV_32F, bytes ? 1 / 255.0 : 1.0);
    EXPECT_LE(cv::norm(p, expected[c + 1], cv::NORM_INF), bytes ? 0.51 / 255 : 1e-4)
        << "channel " << c;
  }
}

TEST(SegmentationNode, LazyOutputWithTheInputsHeaderAndBadEncodingsCounted) {
  ros::NodeHandle nh;
  ros::Publisher image = nh.advertise<sensor_msgs::Image>("/segmentation_test/image", 2);
  const auto idle =
      waitForMessage<diagnostic_msgs::DiagnosticArray>("/segmentation/statistics", 30);
  ASSERT_TRUE(idle) << "no statistics from the segmentation node";
  EXPECT_EQ(statisticsCounts(*idle)["subscribed to the image"], 0u);
  EXPECT_EQ(image.getNumSubscribers(), 0u) << "subscribed to the image with no one listening";

  std::mutex mutex;
  std::vector<sensor_msgs::ImageConstPtr> outputs;
  const boost::function<void(const sensor_msgs::ImageConstPtr&)> keep =
      [&](const sensor_msgs::ImageConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        outputs.push_back(m);
      };
  ros::Subscriber output = nh.subscribe<sensor_msgs::Image>("/segmentation/probability", 5, keep);
  ASSERT_TRUE(waitUntil([&] { return image.getNumSubscribers() == 1; }, 10));
  const auto count = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    return outputs.size();
  };

  const cv::Mat bgr = cv::imread(g_rgb, cv::IMREAD_COLOR);
  ASSERT_FALSE(bgr.empty()) << g_rgb;
  image.publish(imageMessage(bgr, "bgr8", 100));
  ASSERT_TRUE(waitUntil([&] { return count() == 1; }, 20));
  EXPECT_EQ(outputs[0]->header.stamp, ros::Time(100, 5));
  EXPECT_EQ(outputs[0]->header.frame_id, "camera_optical_frame");
  EXPECT_EQ(outputs[0]->encoding, g_depth + "C6");
  EXPECT_EQ(outputs[0]->width, 640u);
  EXPECT_EQ(outputs[0]->height, 480u);
  expectNetworksMaps(*outputs[0], bgr);

  image.publish(imageMessage(cv::Mat(480, 640, CV_16UC1, cv::Scalar(500)), "mono16", 101));
  ros::WallDuration(0.5).sleep();
  image.publish(imageMessage(bgr, "rgb8", 102));
  ASSERT_TRUE(waitUntil([&] { return count() == 2; }, 20)) << "no output after a bad image";
  EXPECT_EQ(outputs[1]->header.stamp, ros::Time(102, 5));
  const auto stats = waitForMessage<diagnostic_msgs::DiagnosticArray>(
      "/segmentation/statistics", 10, [](const diagnostic_msgs::DiagnosticArray& m) {
        return statisticsCounts(m)["images received"] == 3;
      });
  ASSERT_TRUE(stats);
  auto counts = statisticsCounts(*stats);
  EXPECT_EQ(counts["images segmented"], 2u);
  EXPECT_EQ(counts["images rejected: encoding"], 1u);
  EXPECT_EQ(counts["images rejected"], 1u);
  EXPECT_EQ(counts["subscribed to the image"], 1u);

  output.shutdown();
  EXPECT_TRUE(waitUntil([&] { return image.getNumSubscribers() == 0; }, 10))
      << "still subscribed to the image with no one listening";
}

}  // namespace
}  // namespace stocs_ros::test

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_segmentation_node");
  ros::NodeHandle pnh("~");
  pnh.getParam("rgb", stocs_ros::test::g_rgb);
  pnh.getParam("depth", stocs_ros::test::g_depth);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
