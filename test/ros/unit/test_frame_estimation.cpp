// One frame from messages to poses, on the generated box frame loaded as the scene publisher loads
// it: both input forms find the known pose, and bad inputs are named in the error.
#include <cv_bridge/cv_bridge.h>
#include <gtest/gtest.h>

#include <boost/make_shared.hpp>

#include <cmath>
#include <fstream>
#include <limits>

#include <opencv2/imgproc.hpp>
#include "stocs/util/error.h"
#include "stocs_ros/common/cloud_conversion.h"
#include "stocs_ros/scene_publisher/bop_frame.h"
#include "stocs_ros/stocs_node/frame_estimation.h"
#include "stocs_ros/stocs_node/result_messages.h"
#include "test_support.h"

namespace stocs_ros {
namespace {

class FrameEstimation : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::filesystem::path(stocs::test::scratchDir("frame_estimation"));
    truth_ = stocs::test::writeSyntheticBopDataset(*dir_ / "data");
    const stocs::BopDataset dataset(*dir_ / "data");
    frame_ = new BopFrame(loadBopFrame(dataset, 0, 0, dataset.sceneCameras(0).at(0), {1, 2},
                                       *stocs::makeProbabilitySource("real", dataset, 0)));
  }
  static void TearDownTestSuite() {
    delete frame_;
    delete dir_;
  }

  static std::shared_ptr<const EstimationSetup> setup(const std::string& input) {
    std::ofstream(*dir_ / "node.yaml")
        << "objects:\n  - {name: box, model: data/models/obj_000001.ply}\n"
        << "model_cache: cache\n"
        << input;
    return EstimationSetup::load(*dir_ / "node.yaml", {}, [](const std::string&) {});
  }

  static sensor_msgs::ImagePtr image(const std::string& encoding, const cv::Mat& pixels) {
    std_msgs::Header header;
    header.frame_id = "camera";
    return cv_bridge::CvImage(header, encoding, pixels).toImageMsg();
  }

  static EstimationJob cloudJob(double stamp = 3.0) {
    EstimationJob job;
    auto cloud = boost::make_shared<sensor_msgs::PointCloud2>(cloudToMsg(frame_->cloud, cv::Mat()));
    cloud->header.frame_id = "camera";
    cloud->header.stamp = ros::Time(stamp);
    job.frame.cloud = cloud;
    job.frame.probabilities = {image("32FC1", frame_->probabilities[0])};
    job.objects = {0};
    return job;
  }

  void expectFoundNearTruth(const FrameResult& result) const {
    ASSERT_EQ(result.objects.size(), 1u);
    const stocs::PoseEstimate& e = result.objects[0].estimate;
    ASSERT_TRUE(e.found());
    EXPECT_LT((e.best().pose.translation() - truth_.translation()).norm(), 0.005f);
    EXPECT_LT(Eigen::AngleAxisf(e.best().pose.linear().transpose() * truth_.linear()).angle(),
              0.05f);
  }

  static std::string errorOf(const EstimationJob& job, const EstimationSetup& s) {
    try {
      detectJob(job, s);
    } catch (const stocs::InputError& e) {
      return e.what();
    }
    return "";
  }

  static std::filesystem::path* dir_;
  static BopFrame* frame_;
  static Eigen::Isometry3f truth_;
};

std::filesystem::path* FrameEstimation::dir_ = nullptr;
BopFrame* FrameEstimation::frame_ = nullptr;
Eigen::Isometry3f FrameEstimation::truth_;

TEST_F(FrameEstimation, LoadedFrameHoldsTheDatasetImages) {
  EXPECT_EQ(frame_->camera.width, 320);
  EXPECT_EQ(frame_->camera.fx, 300);
  EXPECT_TRUE(frame_->bgr.empty());
  EXPECT_TRUE(frame_->boundary.empty());
  ASSERT_EQ(frame_->probabilities.size(), 2u);
  EXPECT_GT(cv::countNonZero(frame_->probabilities[0]), 1000);
  EXPECT_EQ(cv::countNonZero(frame_->probabilities[1]), 0);  // no map for object 2
  EXPECT_EQ(frame_->objects_without_map, std::vector<int>{2});
  int valid = 0;
  for (int v = 0; v < frame_->depth.rows; ++v) {
    for (int u = 0; u < frame_->depth.cols; ++u) {
      const float d = frame_->depth.at<float>(v, u);
      const bool has_point = frame_->cloud.isValid(v * frame_->cloud.width + u);
      EXPECT_EQ(std::isfinite(d), has_point);
      if (has_point) {
        EXPECT_NEAR(d, frame_->cloud.at(u, v).z(), 1e-6f);
      }
      valid += has_point;
    }
  }
  EXPECT_GT(valid, 1000);
}

TEST_F(FrameEstimation, CloudAndPerObjectImageGiveTheKnownPose) {
  const auto s = setup("");
  const FrameResult result = detectJob(cloudJob(), *s);
  EXPECT_EQ(result.header.stamp, ros::Time(3.0));
  EXPECT_EQ(result.header.frame_id, "camera");
  expectFoundNearTruth(result);
}

TEST_F(FrameEstimation, DepthImageAndMultichannelImageGiveTheKnownPose) {
  const auto s = setup(
      "input: {source: depth, probability: multichannel, channels: [\"-\", box], boundary: "
      "true}\n");
  sensor_msgs::CameraInfo info;
  info.width = frame_->camera.width;
  info.height = frame_->camera.height;
  info.K = {
      frame_->camera.fx, 0, frame_->camera.cx, 0, frame_->camera.fy, frame_->camera.cy, 0, 0, 1};
  cv::Mat channels[2] = {cv::Mat::zeros(frame_->depth.size(), CV_8UC1), cv::Mat()};
  frame_->probabilities[0].convertTo(channels[1], CV_8UC1, 255.0);
  cv::Mat merged;
  cv::merge(channels, 2, merged);
  EstimationJob job;
  job.frame.depth = image("32FC1", frame_->depth);
  job.frame.camera_info = boost::make_shared<sensor_msgs::CameraInfo>(info);
  job.frame.multichannel = image("8UC2", merged);
  job.frame.boundary = image("mono8", cv::Mat(frame_->depth.size(), CV_8UC1, cv::Scalar(255)));
  job.objects = {0};
  expectFoundNearTruth(detectJob(job, *s));
}

/// The box's mask in the generated frame (its map above one half).
cv::Mat boxMask(const BopFrame& frame) {
  return frame.probabilities[0] > 0.5f;
}

TEST_F(FrameEstimation, LabelsMasksAndBoxesGiveTheKnownPose) {
  const cv::Mat mask = boxMask(*frame_);
  // Labels: class 3 is the box (input.labels), 0 the background.
  EstimationJob job = cloudJob();
  job.frame.probabilities.clear();
  cv::Mat labels(mask.size(), CV_8UC1, cv::Scalar(0));
  labels.setTo(3, mask);
  job.frame.segmentation.labels = image("mono8", labels);
  expectFoundNearTruth(
      detectJob(job, *setup("input: {probability: labels, labels: [\"-\", \"-\", \"-\", box]}\n")));

  // Masks: class 1 (the box's id), and a mask of another class over the rest of the image.
  auto masks = boost::make_shared<InstanceMaskArray>();
  masks->masks.resize(2);
  masks->masks[0].mask = *image("mono8", mask);
  masks->masks[0].class_id = 1;
  masks->masks[0].score = 0.9f;
  masks->masks[1].mask = *image("mono8", ~mask);
  masks->masks[1].class_id = 2;
  masks->masks[1].score = 1.0f;
  job.frame.segmentation = {};
  job.frame.segmentation.masks = masks;
  expectFoundNearTruth(detectJob(job, *setup("input: {probability: masks}\n")));

  // Boxes: the mask's bounding box, loosened by 10 pixels.
  const cv::Rect r = cv::boundingRect(mask);
  auto boxes = boost::make_shared<Detection2DArray>();
  boxes->detections.resize(1);
  Detection2D& d = boxes->detections[0];
  d.class_id = 1;
  d.score = 0.8f;
  d.x = r.x - 10;
  d.y = r.y - 10;
  d.width = r.width + 20;
  d.height = r.height + 20;
  job.frame.segmentation = {};
  job.frame.segmentation.boxes = boxes;
  expectFoundNearTruth(detectJob(job, *setup("input: {probability: boxes}\n")));
}

TEST_F(FrameEstimation, GeometricInputFindsTheKnownPoseFromTheCloudAlone) {
  EstimationJob job = cloudJob();
  job.frame.probabilities.clear();
  stocs::GeometricSegmenter segmenter;
  const auto geometric = setup("input: {probability: geometric}\n");
  expectFoundNearTruth(detectJob(job, *geometric, &segmenter));
  // Its maps mark every region of the object's size: they do not say which object is where.
  EXPECT_FALSE(estimationFrame(job, *geometric, &segmenter).maps_name_objects);
  EXPECT_TRUE(estimationFrame(cloudJob(), *setup(""), nullptr).maps_name_objects);
}

TEST_F(FrameEstimation, GeometricInputNamesAnUnorganizedCloud) {
  EstimationJob job = cloudJob();
  job.frame.probabilities.clear();
  job.frame.cloud =
      boost::make_shared<sensor_msgs::PointCloud2>(cloudToMsg(stocs::OrganizedCloud(100, 1), {}));
  stocs::GeometricSegmenter segmenter;
  try {
    detectJob(job, *setup("input: {probability: geometric}\n"), &segmenter);
    ADD_FAILURE() << "an unorganized cloud was estimated";
  } catch (const stocs::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cloud: cloud is not organized (height 1, width 100)"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(FrameEstimation, GeometricInputNamesADepthWithoutMeasurements) {
  const auto s = setup("input: {source: depth, probability: geometric}\n");
  sensor_msgs::CameraInfo info;
  info.width = frame_->camera.width;
  info.height = frame_->camera.height;
  info.K = {
      frame_->camera.fx, 0, frame_->camera.cx, 0, frame_->camera.fy, frame_->camera.cy, 0, 0, 1};
  EstimationJob job;
  job.frame.depth = image("32FC1", cv::Mat(frame_->depth.size(), CV_32FC1, cv::Scalar(0)));
  job.frame.camera_info = boost::make_shared<sensor_msgs::CameraInfo>(info);
  job.objects = {0};
  stocs::GeometricSegmenter segmenter;
  try {
    detectJob(job, *s, &segmenter);
    ADD_FAILURE() << "a depth image without measurements was estimated";
  } catch (const stocs::InputError& e) {
    EXPECT_STREQ(e.what(), "geometric segmentation: depth image has no valid measurement");
  }
}

TEST_F(FrameEstimation, BadSegmentationMessagesAreNamed) {
  EstimationJob job = cloudJob();
  job.frame.probabilities.clear();
  const auto labels_setup = setup("input: {probability: labels, label_confidence: true}\n");
  EXPECT_EQ(errorOf(job, *labels_setup), "label image: none given for input.probability");
  job.frame.segmentation.labels = image("32FC1", frame_->probabilities[0]);
  EXPECT_NE(errorOf(job, *labels_setup).find("label image: label image has OpenCV type 5"),
            std::string::npos);
  job.frame.segmentation.labels = image("mono8", cv::Mat(frame_->depth.size(), CV_8UC1));
  job.frame.segmentation.label_confidence = image("mono8", cv::Mat(10, 10, CV_8UC1));
  EXPECT_EQ(errorOf(job, *labels_setup),
            "label image: confidence image is 10x10 but the label image is 320x240");

  job.frame.segmentation = {};
  auto masks = boost::make_shared<InstanceMaskArray>();
  masks->masks.resize(1);
  masks->masks[0].mask = *image("mono8", cv::Mat(10, 10, CV_8UC1, cv::Scalar(255)));
  masks->masks[0].class_id = 1;
  masks->masks[0].score = 1;
  job.frame.segmentation.masks = masks;
  const auto masks_setup = setup("input: {probability: masks}\n");
  EXPECT_EQ(errorOf(job, *masks_setup),
            "instance masks: mask 0 (class 1) is 10x10 but the depth image is 320x240");
  masks->masks[0].mask = *image("rgb8", cv::Mat(frame_->depth.size(), CV_8UC3));
  EXPECT_NE(errorOf(job, *masks_setup).find("instance masks: mask 0 (class 1): encoding 'rgb8'"),
            std::string::npos);

  job.frame.segmentation = {};
  auto boxes = boost::make_shared<Detection2DArray>();
  boxes->detections.resize(1);
  boxes->detections[0].width = std::numeric_limits<float>::quiet_NaN();
  boxes->detections[0].height = 5;
  boxes->detections[0].score = 1;
  job.frame.segmentation.boxes = boxes;
  EXPECT_EQ(errorOf(job, *setup("input: {probability: boxes}\n")).substr(0, 30),
            "boxes: box 0 (class 0) is x 0 ");
}

TEST_F(FrameEstimation, TrackedFramesCarryTheirStatesIntoTheMessages) {
  const auto s = setup("");
  ASSERT_TRUE(s->config.tracking.enabled);  // the node's default
  stocs::StreamTracker tracker(s->config.tracking);
  // The first frame is detected in place.
  const FrameResult first = trackJob(cloudJob(3.0), s, tracker);
  expectFoundNearTruth(first);
  EXPECT_EQ(first.objects[0].states,
            std::vector<stocs::TrackState>{stocs::TrackState::kRedetected});
  ASSERT_TRUE(first.tracking);
  EXPECT_EQ(first.tracking->redetected, 1);
  EXPECT_EQ(toObjectPoseArray(first, *s).objects.at(0).state, ObjectPose::REDETECTED);

  // The next is followed, and starts the detection that confirms the new track.
  const FrameResult next = trackJob(cloudJob(3.0 + 1.0 / 30), s, tracker);
  expectFoundNearTruth(next);
  EXPECT_EQ(next.objects[0].states, std::vector<stocs::TrackState>{stocs::TrackState::kTracked});
  EXPECT_EQ(toObjectPoseArray(next, *s).objects.at(0).state, ObjectPose::TRACKED);
  tracker.waitForDetection();
  expectFoundNearTruth(trackJob(cloudJob(3.0 + 2.0 / 30), s, tracker));  // merges it

  // The map vanishes: the box is lost, listed as rejected and lost, with no pose published.
  EstimationJob gone = cloudJob(3.0 + 3.0 / 30);
  gone.frame.probabilities[0] = image("32FC1", cv::Mat(240, 320, CV_32FC1, cv::Scalar(0)));
  const FrameResult lost = trackJob(gone, s, tracker);
  EXPECT_EQ(lost.objects[0].states, std::vector<stocs::TrackState>{stocs::TrackState::kLost});
  const ObjectPoseArray lost_msg = toObjectPoseArray(lost, *s);
  EXPECT_TRUE(lost_msg.objects.empty());
  ASSERT_EQ(lost_msg.rejected.size(), 1u);
  EXPECT_TRUE(lost_msg.rejected[0].lost);
  EXPECT_EQ(lost_msg.rejected[0].reason.rfind("lost: ", 0), 0u) << lost_msg.rejected[0].reason;

  // Detection without tracking says so.
  EXPECT_EQ(toObjectPoseArray(detectJob(cloudJob(), *s), *s).objects.at(0).state,
            ObjectPose::DETECTED);
}

TEST_F(FrameEstimation, ColourImageReachesTheFrameBeforeTheCloudsColour) {
  const auto s = setup("input: {colour: true}\n");
  EstimationJob job = cloudJob();
  cv::Mat cloud_colour(240, 320, CV_8UC3, cv::Scalar(1, 2, 3));
  auto cloud =
      boost::make_shared<sensor_msgs::PointCloud2>(cloudToMsg(frame_->cloud, cloud_colour));
  cloud->header = job.frame.cloud->header;
  job.frame.cloud = cloud;
  EXPECT_EQ(convertFrame(job, s->config).colour.at<cv::Vec3b>(5, 7), cv::Vec3b(1, 2, 3));
  job.frame.colour = image("rgb8", cv::Mat(240, 320, CV_8UC3, cv::Scalar(30, 20, 10)));
  const stocs::Frame frame = convertFrame(job, s->config);
  ASSERT_EQ(frame.colour.type(), CV_8UC3);
  EXPECT_EQ(frame.colour.at<cv::Vec3b>(5, 7), cv::Vec3b(10, 20, 30));
  expectFoundNearTruth(detectJob(job, *s));
}

TEST_F(FrameEstimation, BadInputsAreNamed) {
  const auto s = setup("");
  EstimationJob colour = cloudJob();
  colour.frame.probabilities[0] = image("bgr8", cv::Mat(240, 320, CV_8UC3, cv::Scalar(0)));
  EXPECT_NE(errorOf(colour, *s).find("probability image of 'box': encoding 'bgr8'"),
            std::string::npos)
      << errorOf(colour, *s);

  EstimationJob missing = cloudJob();
  missing.frame.probabilities[0].reset();
  EXPECT_EQ(errorOf(missing, *s), "object 'box': the frame has no probability image");

  EstimationJob small = cloudJob();
  small.frame.probabilities[0] = image("mono8", cv::Mat(10, 10, CV_8UC1, cv::Scalar(255)));
  EXPECT_NE(
      errorOf(small, *s).find("object 'box': probability image is 10x10 but the cloud is 320x240"),
      std::string::npos)
      << errorOf(small, *s);

  EstimationJob nan = cloudJob();
  stocs::OrganizedCloud nothing(320, 240);
  nan.frame.cloud = boost::make_shared<sensor_msgs::PointCloud2>(cloudToMsg(nothing, cv::Mat()));
  EXPECT_NE(errorOf(nan, *s).find("cloud: organized cloud 320x240 has too few valid points (0)"),
            std::string::npos)
      << errorOf(nan, *s);

  EstimationJob wrong_boundary = cloudJob();
  wrong_boundary.frame.boundary = image("mono16", cv::Mat(240, 320, CV_16UC1, cv::Scalar(0)));
  EXPECT_NE(errorOf(wrong_boundary, *s).find("boundary image: "), std::string::npos);

  EstimationJob mono_colour = cloudJob();
  mono_colour.frame.colour = image("mono8", cv::Mat(240, 320, CV_8UC1, cv::Scalar(0)));
  EXPECT_NE(errorOf(mono_colour, *s).find("colour image: colour image has encoding 'mono8'"),
            std::string::npos)
      << errorOf(mono_colour, *s);
  EstimationJob small_colour = cloudJob();
  small_colour.frame.colour = image("rgb8", cv::Mat(120, 160, CV_8UC3, cv::Scalar(0)));
  EXPECT_NE(errorOf(small_colour, *s).find("colour image: 160x120 image does not fit the 320x240"),
            std::string::npos)
      << errorOf(small_colour, *s);

  EstimationJob budget = cloudJob();
  budget.time_budget = 7200;
  EXPECT_NE(errorOf(budget, *s).find("time_budget 7200 s is outside [0, 3600]"), std::string::npos)
      << errorOf(budget, *s);
}

}  // namespace
}  // namespace stocs_ros
