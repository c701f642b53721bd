// PointCloud2 and depth image + camera_info to the core's organized cloud, and back.
#include <cv_bridge/cv_bridge.h>
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "stocs/util/error.h"
#include "stocs_ros/common/cloud_conversion.h"

namespace stocs_ros {
namespace {

stocs::OrganizedCloud smallCloud() {
  stocs::OrganizedCloud cloud(4, 3);
  for (int i = 0; i < 12; ++i) {
    if (i != 5) cloud.points[i] = Eigen::Vector3f(0.01f * i, -0.02f * i, 0.5f + 0.1f * i);
  }
  return cloud;
}

void expectSameCloud(const stocs::OrganizedCloud& a, const stocs::OrganizedCloud& b) {
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  for (size_t i = 0; i < a.points.size(); ++i) {
    ASSERT_EQ(a.isValid(static_cast<int>(i)), b.isValid(static_cast<int>(i))) << i;
    if (a.isValid(static_cast<int>(i))) {
      EXPECT_EQ(a.points[i], b.points[i]) << i;
    }
  }
}

std::string conversionError(const sensor_msgs::PointCloud2& msg) {
  try {
    cloudFromMsg(msg);
  } catch (const stocs::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(CloudConversion, XyzAndXyzrgbCloudsRoundTrip) {
  const stocs::OrganizedCloud cloud = smallCloud();
  const sensor_msgs::PointCloud2 xyz = cloudToMsg(cloud, cv::Mat());
  EXPECT_EQ(xyz.fields.size(), 3u);
  expectSameCloud(cloudFromMsg(xyz), cloud);

  const cv::Mat bgr(3, 4, CV_8UC3, cv::Scalar(10, 20, 30));
  const sensor_msgs::PointCloud2 xyzrgb = cloudToMsg(cloud, bgr);
  EXPECT_EQ(xyzrgb.fields.size(), 4u);
  EXPECT_EQ(xyzrgb.width, 4u);
  EXPECT_EQ(xyzrgb.height, 3u);
  expectSameCloud(cloudFromMsg(xyzrgb), cloud);
}

TEST(CloudConversion, RowPaddingIsSkipped) {
  const stocs::OrganizedCloud cloud = smallCloud();
  const sensor_msgs::PointCloud2 tight = cloudToMsg(cloud, cv::Mat());
  sensor_msgs::PointCloud2 padded = tight;
  padded.row_step = tight.row_step + 8;
  padded.data.assign(padded.row_step * padded.height, 0);
  for (uint32_t v = 0; v < tight.height; ++v) {
    std::copy_n(&tight.data[v * tight.row_step], tight.row_step, &padded.data[v * padded.row_step]);
  }
  expectSameCloud(cloudFromMsg(padded), cloud);
}

TEST(CloudConversion, BadCloudsAreNamed) {
  const sensor_msgs::PointCloud2 good = cloudToMsg(smallCloud(), cv::Mat());
  sensor_msgs::PointCloud2 empty;
  EXPECT_EQ(conversionError(empty), "cloud is empty (0x0)");
  sensor_msgs::PointCloud2 flat = good;
  flat.width = 12;
  flat.height = 1;
  EXPECT_NE(conversionError(flat).find("not organized"), std::string::npos);
  sensor_msgs::PointCloud2 no_z = good;
  no_z.fields.pop_back();
  EXPECT_EQ(conversionError(no_z), "cloud has no float32 field 'z' within its point step");
  sensor_msgs::PointCloud2 doubles = good;
  doubles.fields[0].datatype = sensor_msgs::PointField::FLOAT64;
  EXPECT_NE(conversionError(doubles).find("field 'x'"), std::string::npos);
  sensor_msgs::PointCloud2 truncated = good;
  truncated.data.resize(truncated.data.size() / 2);
  EXPECT_NE(conversionError(truncated).find("data bytes"), std::string::npos);
}

TEST(CloudConversion, ColourComesFromThePackedRgbField) {
  const stocs::OrganizedCloud cloud = smallCloud();
  EXPECT_TRUE(colourFromCloudMsg(cloudToMsg(cloud, cv::Mat())).empty());
  cv::Mat bgr(3, 4, CV_8UC3, cv::Scalar(10, 20, 30));
  bgr.at<cv::Vec3b>(2, 1) = cv::Vec3b(200, 100, 50);
  const cv::Mat colour = colourFromCloudMsg(cloudToMsg(cloud, bgr));
  ASSERT_EQ(colour.type(), CV_8UC3);
  EXPECT_EQ(colour.at<cv::Vec3b>(0, 0), cv::Vec3b(10, 20, 30));
  EXPECT_EQ(colour.at<cv::Vec3b>(2, 1), cv::Vec3b(200, 100, 50));
}

TEST(CloudConversion, BadRgbFieldsAreNamed) {
  const sensor_msgs::PointCloud2 good = cloudToMsg(smallCloud(), cv::Mat(3, 4, CV_8UC3));
  const auto error = [](const sensor_msgs::PointCloud2& msg) {
    try {
      colourFromCloudMsg(msg);
    } catch (const stocs::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  sensor_msgs::PointCloud2 bytes = good;
  bytes.fields[3].datatype = sensor_msgs::PointField::UINT8;
  EXPECT_EQ(error(bytes), "cloud field 'rgb' is not a packed 4-byte colour within its point step");
  sensor_msgs::PointCloud2 outside = good;
  outside.fields[3].offset = outside.point_step - 2;
  EXPECT_EQ(error(outside),
            "cloud field 'rgb' is not a packed 4-byte colour within its point step");
}

// Regression (fuzz_ros_cloud): offset + 4 wrapped in 32 bits, so an offset near 2^32 passed the
// point-step check and the copy read far outside the data.
TEST(CloudConversion, FieldOffsetNearTheTopOfUint32IsRejected) {
  sensor_msgs::PointCloud2 wrapped = cloudToMsg(smallCloud(), cv::Mat());
  wrapped.fields[2].offset = 0xFFFFFFFFu;
  EXPECT_EQ(conversionError(wrapped), "cloud has no float32 field 'z' within its point step");
}

TEST(CloudConversion, DepthImagesInMillimetresAndMetresGiveTheSameCloud) {
  sensor_msgs::CameraInfo info;
  info.width = 4;
  info.height = 3;
  info.K = {100, 0, 2, 0, 110, 1.5, 0, 0, 1};
  cv::Mat mm(3, 4, CV_16UC1, cv::Scalar(800));
  mm.at<uint16_t>(1, 2) = 0;
  cv::Mat m;
  mm.convertTo(m, CV_32FC1, 0.001);
  const std_msgs::Header header;
  const stocs::OrganizedCloud from_mm =
      cloudFromDepthImage(cv_bridge::CvImage(header, "16UC1", mm).toImageMsg(), info);
  const stocs::OrganizedCloud from_m =
      cloudFromDepthImage(cv_bridge::CvImage(header, "32FC1", m).toImageMsg(), info);
  EXPECT_EQ(from_mm.validCount(), 11);
  ASSERT_EQ(from_m.validCount(), 11);
  for (size_t i = 0; i < from_mm.points.size(); ++i) {
    if (from_mm.isValid(static_cast<int>(i))) {
      EXPECT_TRUE(from_mm.points[i].isApprox(from_m.points[i], 1e-6f));
    }
  }
  EXPECT_TRUE(
      from_mm.at(0, 0).isApprox(Eigen::Vector3f(-2 * 0.8f / 100, -1.5f * 0.8f / 110, 0.8f)));

  EXPECT_THROW(cloudFromDepthImage(
                   cv_bridge::CvImage(header, "mono8", cv::Mat(3, 4, CV_8UC1)).toImageMsg(), info),
               stocs::InputError);
  try {
    cloudFromDepthImage(cv_bridge::CvImage(header, "rgb8", cv::Mat(3, 4, CV_8UC3)).toImageMsg(),
                        info);
    ADD_FAILURE() << "an rgb8 depth image was taken";
  } catch (const stocs::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "depth image has encoding 'rgb8'; REP 118 depth is 16UC1 (mm) or 32FC1 (m)");
  }
  sensor_msgs::CameraInfo no_focal = info;
  no_focal.K[0] = 0;
  EXPECT_THROW(intrinsicsFromCameraInfo(no_focal), stocs::InputError);
  sensor_msgs::CameraInfo binned = info;
  binned.binning_x = 2;
  EXPECT_THROW(intrinsicsFromCameraInfo(binned), stocs::InputError);
  sensor_msgs::CameraInfo other_size = info;
  other_size.width = 8;
  EXPECT_THROW(
      cloudFromDepthImage(cv_bridge::CvImage(header, "16UC1", mm).toImageMsg(), other_size),
      stocs::InputError);
}

}  // namespace
}  // namespace stocs_ros
