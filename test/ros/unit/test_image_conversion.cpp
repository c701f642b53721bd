// Probability, boundary and colour images from sensor_msgs/Image: every accepted encoding and the
// rejected ones, with the encoding or size in the message.
#include <cv_bridge/cv_bridge.h>
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "stocs/util/error.h"
#include "stocs_ros/common/image_conversion.h"

namespace stocs_ros {
namespace {

sensor_msgs::ImagePtr image(const std::string& encoding, const cv::Mat& pixels) {
  return cv_bridge::CvImage(std_msgs::Header(), encoding, pixels).toImageMsg();
}

template <class Convert>
std::string errorOf(Convert&& convert) {
  try {
    convert();
  } catch (const stocs::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ImageConversion, ProbabilityEncodingsAreScaled) {
  cv::Mat f(2, 3, CV_32FC1, cv::Scalar(0.25f));
  EXPECT_FLOAT_EQ(probabilityFromImage(image("32FC1", f), 10000).at<float>(1, 2), 0.25f);
  cv::Mat u16(2, 3, CV_16UC1, cv::Scalar(5000));
  EXPECT_FLOAT_EQ(probabilityFromImage(image("mono16", u16), 10000).at<float>(0, 0), 0.5f);
  EXPECT_FLOAT_EQ(probabilityFromImage(image("16UC1", u16), 5000).at<float>(0, 0), 1.0f);
  cv::Mat u8(2, 3, CV_8UC1, cv::Scalar(51));
  EXPECT_FLOAT_EQ(probabilityFromImage(image("mono8", u8), 10000).at<float>(0, 0), 0.2f);
}

TEST(ImageConversion, BadProbabilityImagesAreNamed) {
  const cv::Mat bgr(2, 3, CV_8UC3, cv::Scalar(1, 2, 3));
  EXPECT_NE(errorOf([&] { probabilityFromImage(image("rgb8", bgr), 10000); }).find("'rgb8'"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              probabilityFromImage(image("16SC1", cv::Mat(2, 3, CV_16SC1)), 10000);
            }).find("'16SC1'"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              probabilityFromImage(image("32FC2", cv::Mat(2, 3, CV_32FC2)), 10000);
            }).find("2 channels"),
            std::string::npos);
  cv::Mat above(2, 3, CV_16UC1, cv::Scalar(20000));
  EXPECT_NE(
      errorOf([&] { probabilityFromImage(image("mono16", above), 10000); }).find("outside [0, 1]"),
      std::string::npos);
  sensor_msgs::ImagePtr short_rows = image("32FC1", cv::Mat(2, 3, CV_32FC1, cv::Scalar(0)));
  short_rows->step = 8;
  EXPECT_NE(errorOf([&] { probabilityFromImage(short_rows, 10000); }).find("step 8"),
            std::string::npos);
  sensor_msgs::ImagePtr truncated = image("32FC1", cv::Mat(2, 3, CV_32FC1, cv::Scalar(0)));
  truncated->data.resize(4);
  EXPECT_NE(errorOf([&] { probabilityFromImage(truncated, 10000); }).find("4 data bytes"),
            std::string::npos);
  sensor_msgs::ImagePtr empty = image("32FC1", cv::Mat(2, 3, CV_32FC1));
  empty->width = 0;
  EXPECT_NE(errorOf([&] { probabilityFromImage(empty, 10000); }).find("empty"), std::string::npos);
}

// Regression (fuzz_ros_image): more data than step x height passed our check and cv_bridge then
// threw its own exception, which is not an InputError.
TEST(ImageConversion, DataLongerThanStepTimesHeightIsAnInputError) {
  sensor_msgs::ImagePtr longer = image("mono16", cv::Mat(2, 2, CV_16UC1, cv::Scalar(700)));
  longer->data.push_back(0);
  EXPECT_NE(errorOf([&] { probabilityFromImage(longer, 10000); }).find("9 data bytes"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { boundaryFromImage(longer); }).find("step x height"), std::string::npos);
}

// Regression (fuzz_ros_image): a step that is not a whole number of values made cv::Mat throw
// cv::Exception.
TEST(ImageConversion, StepThatSplitsAValueIsAnInputError) {
  sensor_msgs::ImagePtr odd = image("mono16", cv::Mat(2, 2, CV_16UC1, cv::Scalar(700)));
  odd->step = 5;
  odd->data.resize(10);
  EXPECT_NE(errorOf([&] { probabilityFromImage(odd, 10000); }).find("not a multiple of its 2-byte"),
            std::string::npos);
}

TEST(ImageConversion, MultichannelImagesSplitIntoChannels) {
  std::vector<cv::Mat> planes = {cv::Mat(2, 3, CV_16UC1, cv::Scalar(0)),
                                 cv::Mat(2, 3, CV_16UC1, cv::Scalar(10000)),
                                 cv::Mat(2, 3, CV_16UC1, cv::Scalar(2500))};
  cv::Mat merged;
  cv::merge(planes, merged);
  const std::vector<cv::Mat> p = probabilitiesFromChannels(image("16UC3", merged), 3, 10000);
  ASSERT_EQ(p.size(), 3u);
  EXPECT_FLOAT_EQ(p[0].at<float>(1, 1), 0.0f);
  EXPECT_FLOAT_EQ(p[1].at<float>(1, 1), 1.0f);
  EXPECT_FLOAT_EQ(p[2].at<float>(1, 1), 0.25f);
  EXPECT_NE(errorOf([&] {
              probabilitiesFromChannels(image("16UC3", merged), 4, 10000);
            }).find("the config names 4"),
            std::string::npos);
  planes[2].setTo(12000);
  cv::merge(planes, merged);
  EXPECT_NE(errorOf([&] {
              probabilitiesFromChannels(image("16UC3", merged), 3, 10000);
            }).find("channel 2: "),
            std::string::npos);
}

TEST(ImageConversion, BoundaryMapsAreMono8) {
  cv::Mat interior(2, 3, CV_8UC1, cv::Scalar(255));
  EXPECT_EQ(boundaryFromImage(image("mono8", interior)).at<uint8_t>(1, 2), 255);
  EXPECT_NE(errorOf([&] {
              boundaryFromImage(image("mono16", cv::Mat(2, 3, CV_16UC1)));
            }).find("'mono16'"),
            std::string::npos);
}

TEST(ImageConversion, ColourImagesBecomeBgr) {
  const cv::Mat bgr(2, 3, CV_8UC3, cv::Scalar(10, 20, 30));
  const cv::Vec3b expected(10, 20, 30);
  EXPECT_EQ(colourFromImage(image("bgr8", bgr)).at<cv::Vec3b>(1, 2), expected);
  const cv::Mat rgb(2, 3, CV_8UC3, cv::Scalar(30, 20, 10));
  EXPECT_EQ(colourFromImage(image("rgb8", rgb)).at<cv::Vec3b>(1, 2), expected);
  const cv::Mat rgba(2, 3, CV_8UC4, cv::Scalar(30, 20, 10, 255));
  EXPECT_EQ(colourFromImage(image("rgba8", rgba)).at<cv::Vec3b>(0, 0), expected);
  const cv::Mat bgr16(2, 3, CV_16UC3, cv::Scalar(10 * 257, 20 * 257, 30 * 257));
  const cv::Mat from16 = colourFromImage(image("bgr16", bgr16));
  EXPECT_EQ(from16.type(), CV_8UC3);
  EXPECT_EQ(from16.at<cv::Vec3b>(1, 1), expected);
}

TEST(ImageConversion, BadColourImagesAreNamed) {
  EXPECT_NE(errorOf([&] {
              colourFromImage(image("mono8", cv::Mat(2, 3, CV_8UC1, cv::Scalar(0))));
            }).find("colour image has encoding 'mono8'"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              colourFromImage(image("32FC1", cv::Mat(2, 3, CV_32FC1, cv::Scalar(0))));
            }).find("'32FC1'"),
            std::string::npos);
  sensor_msgs::ImagePtr truncated = image("rgb8", cv::Mat(2, 3, CV_8UC3, cv::Scalar(0)));
  truncated->data.resize(5);
  EXPECT_NE(errorOf([&] { colourFromImage(truncated); }).find("5 data bytes"), std::string::npos);
  sensor_msgs::ImagePtr empty = image("bgr8", cv::Mat(2, 3, CV_8UC3, cv::Scalar(0)));
  empty->height = 0;
  EXPECT_NE(errorOf([&] { colourFromImage(empty); }).find("empty"), std::string::npos);
}

}  // namespace
}  // namespace stocs_ros
