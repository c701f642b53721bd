// The C++ interface (stocs/stocs.h): an Estimator owning or sharing its models finds a known pose
// in a Frame, through the same frame loop as the CLI and the node, and names what is wrong with a
// request.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>

#include "stocs/eval/pose_metrics.h"
#include "stocs/io/ply_writer.h"
#include "stocs/sim/shape_meshes.h"
#include "stocs/stocs.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

class EstimatorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const CameraIntrinsics camera = test::testCamera();
    truth_ = test::viewingPose(0.6f);
    cv::Mat labels;
    const cv::Mat depth = test::renderDepth({{asymmetricMesh(), truth_}}, camera, &labels);
    frame_ = Frame::fromDepth(depth, camera, 1.0);
    cv::Mat probability(labels.size(), CV_32FC1, cv::Scalar(0));
    probability.setTo(0.9f, labels == 1);
    frame_.probabilities["block"] = probability;
    model_file_ = (test::scratchDir("estimator") / "block.ply").string();
    writePly(model_file_, asymmetricMesh(), 1000.0f);  // in mm, as BOP models
  }

  double adds(const PoseEstimate& e, const PreparedModel& model) const {
    return addsError(
        model.model.points,
        {e.best().pose.linear().cast<double>(), e.best().pose.translation().cast<double>()},
        {truth_.linear().cast<double>(), truth_.translation().cast<double>()});
  }

  Eigen::Isometry3f truth_;
  Frame frame_;
  std::string model_file_;
};

TEST_F(EstimatorTest, FindsTheObjectOfAFrameWithAModelFromAFile) {
  Estimator estimator(PipelineParams{}, ModelCache(test::scratchDir("estimator_cache")));
  estimator.addObject("block", model_file_);
  const std::vector<ObjectResult> results = estimator.estimate(frame_);
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].name, "block");
  const PoseEstimate& e = results[0].estimate;
  ASSERT_TRUE(e.found());
  EXPECT_LT(adds(e, *estimator.model("block")), 0.1 * estimator.model("block")->model.diameter);
  EXPECT_GT(e.segment_points, 0u);
  EXPECT_GE(e.seconds, e.stages.segment);
  // The one-object call gives the same estimate.
  EXPECT_TRUE(estimator.estimate(frame_, "block").best().pose.isApprox(e.best().pose));
}

TEST_F(EstimatorTest, EstimatorsShareAPreparedModelAndSkipObjectsWithoutAMap) {
  Estimator first(PipelineParams{}, ModelCache(test::scratchDir("estimator_cache")));
  first.addObject("block", model_file_);
  Estimator second;
  second.addObject("block", first.model("block"));
  second.addObject("other", first.model("block"));
  EXPECT_EQ(second.model("block"), first.model("block"));  // shared, not copied
  const std::vector<ObjectResult> results = second.estimate(frame_);
  ASSERT_EQ(results.size(), 1u);  // "other" has no map in the frame
  EXPECT_TRUE(results[0].estimate.found());
}

TEST_F(EstimatorTest, BadRequestsAreNamed) {
  Estimator estimator;
  estimator.addObject("block", std::make_shared<const PreparedModel>(PreparedModel{}));
  EXPECT_THROW(estimator.addObject("block", model_file_), InputError);
  try {
    estimator.estimate(frame_, "ghost");
    ADD_FAILURE() << "an unknown object was estimated";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "unknown object 'ghost'");
  }
  Frame small = frame_;
  small.probabilities["block"] = cv::Mat(10, 10, CV_32FC1, cv::Scalar(0.5f));
  try {
    estimator.estimate(small, "block");
    ADD_FAILURE() << "a map of another size was estimated";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "object 'block': probability image is 10x10 but the cloud is 320x240");
  }
  Frame coloured = frame_;
  coloured.colour = cv::Mat(480, 640, CV_8UC3);
  try {
    estimator.estimate(coloured, "block");
    ADD_FAILURE() << "a colour image of another size was estimated";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "object 'block': colour image 640x480 does not fit the 320x240 cloud");
  }
  coloured.colour = cv::Mat(240, 320, CV_8UC1);
  EXPECT_THROW(estimator.estimate(coloured, "block"), InputError);
  PipelineParams bad;
  bad.stocs.bases = 0;
  EXPECT_THROW(Estimator{bad}, InputError);
}

TEST_F(EstimatorTest, TheFrameLoopRunsAnyMethodAndRequiresEveryRequestedMap) {
  const PreparedModel model;
  int calls = 0;
  const ObjectEstimator counting = [&](const ObjectInput& in) {
    ++calls;
    EXPECT_EQ(in.cloud, &frame_.cloud);
    EXPECT_EQ(in.model, &model);
    EXPECT_EQ(in.camera->fx, frame_.camera->fx);
    EXPECT_EQ(in.colour, frame_.colour.empty() ? nullptr : &frame_.colour);
    return PoseEstimate{};
  };
  EXPECT_EQ(estimateFrame(frame_, {{"block", &model}}, PipelineParams{}, counting).size(), 1u);
  frame_.colour = cv::Mat(frame_.cloud.height, frame_.cloud.width, CV_8UC3, cv::Scalar(0, 0, 255));
  EXPECT_EQ(estimateFrame(frame_, {{"block", &model}}, PipelineParams{}, counting).size(), 1u);
  EXPECT_EQ(calls, 2);
  try {
    estimateFrame(frame_, {{"block", &model}, {"mug", &model}}, PipelineParams{}, counting);
    ADD_FAILURE() << "an object without a map was estimated";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "object 'mug': the frame has no probability image");
  }
}

TEST_F(EstimatorTest, AnObjectWhosePoseAnotherExplainsIsSearchedForAgainElsewhere) {
  // The block at truth_ and its twin (the same shape) 15 cm to the side. The twin's map marks both,
  // fainter than the block's own map marks the block; its estimator poses it on the block wherever
  // its map allows that, else on the twin: on the block only the second search moves it.
  const CameraIntrinsics camera = test::testCamera();
  Eigen::Isometry3f twin = truth_;
  twin.translation().x() += 0.15f;
  cv::Mat labels;
  const cv::Mat depth =
      test::renderDepth({{asymmetricMesh(), truth_}, {asymmetricMesh(), twin}}, camera, &labels);
  Frame frame = Frame::fromDepth(depth, camera, 1.0);
  cv::Mat block_map(labels.size(), CV_32FC1, cv::Scalar(0));
  block_map.setTo(0.9f, labels == 1);
  frame.probabilities["block"] = block_map;
  cv::Mat twin_map(labels.size(), CV_32FC1, cv::Scalar(0));
  twin_map.setTo(0.6f, labels == 1);
  twin_map.setTo(0.6f, labels == 2);
  frame.probabilities["twin"] = twin_map;

  Estimator estimator(PipelineParams{}, ModelCache(test::scratchDir("estimator_cache")));
  estimator.addObject("block", model_file_);
  const std::vector<FrameObject> objects = {{"block", estimator.model("block").get()},
                                            {"twin", estimator.model("block").get()}};
  auto marks = [&](const ObjectInput& in, const cv::Mat& label) {
    return cv::countNonZero((*in.probability > 0) & label) > 0;
  };
  int calls = 0;
  const ObjectEstimator placing = [&](const ObjectInput& in) {
    PoseEstimate e;
    const bool on_block = marks(in, labels == 1);
    ++calls;
    if (on_block || marks(in, labels == 2)) {
      InstancePose& pose = e.instances.emplace_back();
      pose.pose = on_block ? truth_ : twin;
      pose.confidence = 0.9f;
    }
    return e;
  };
  PipelineParams again;
  again.explanation.search_again = true;
  std::vector<ObjectResult> results = estimateFrame(frame, objects, again, placing);
  ASSERT_EQ(results.size(), 2u);
  EXPECT_TRUE(results[0].estimate.best().accepted);
  const InstancePose& found = results[1].estimate.best();
  EXPECT_TRUE(found.accepted) << found.rejection;
  EXPECT_TRUE(found.pose.isApprox(twin));
  EXPECT_EQ(calls, 3);  // the block, the twin, the twin on its map without the block

  // Without the second search, or where it finds nothing, the twin keeps its explained pose; its
  // confidence reads the share explained.
  results = estimateFrame(frame, objects, PipelineParams{}, placing);
  const InstancePose& explained = results[1].estimate.best();
  EXPECT_EQ(explained.rejection, "explained by block 0");
  EXPECT_GT(explained.evidence.explained, 0.5f);
  EXPECT_FLOAT_EQ(explained.confidence, ConfidenceParams{}.confidence(explained.evidence));
  frame.probabilities["twin"].setTo(0.0f, labels == 2);
  results = estimateFrame(frame, objects, again, placing);
  EXPECT_TRUE(results[1].estimate.best().pose.isApprox(truth_));
  EXPECT_EQ(results[1].estimate.best().rejection, "explained by block 0");
}

TEST_F(EstimatorTest, APoseWhoseSurfaceAnotherPartlyExplainsIsJudgedAgainWithThatShare) {
  // The block at truth_, and a twin posed on it slid by 6 cm along its length, whose map holds the
  // pixels they share more strongly: the twin explains the part of the block's surface it covers
  // (a map of the twin over the whole block would claim the block's pose: test_frame_explanation).
  const CameraIntrinsics camera = test::testCamera();
  const Eigen::Isometry3f slid = truth_ * Eigen::Translation3f(0.06f, 0, 0);
  cv::Mat labels, twin_labels;
  test::renderDepth({{asymmetricMesh(), truth_}}, camera, &labels);
  test::renderDepth({{asymmetricMesh(), slid}}, camera, &twin_labels);
  cv::Mat twin_map(labels.size(), CV_32FC1, cv::Scalar(0));
  twin_map.setTo(0.95f, (labels == 1) & (twin_labels == 1));
  frame_.probabilities["twin"] = twin_map;

  Estimator estimator(PipelineParams{}, ModelCache(test::scratchDir("estimator_cache")));
  estimator.addObject("block", model_file_);
  const std::vector<FrameObject> objects = {{"block", estimator.model("block").get()},
                                            {"twin", estimator.model("block").get()}};
  const ConfidenceParams confidence;
  const ObjectEstimator placing = [&](const ObjectInput& in) {
    PoseEstimate e;
    InstancePose& pose = e.instances.emplace_back();
    pose.pose = in.probability == &frame_.probabilities.at("twin") ? slid : truth_;
    pose.evidence.surface_confirmed = pose.evidence.matched = pose.evidence.consensus = 1;
    pose.evidence.map_support = 0.9f;
    judgePose(pose, confidence);
    return e;
  };
  const float alone =
      placing(objectInput(frame_, camera, {"block", objects[0].model}, PipelineParams{}))
          .best()
          .confidence;
  const std::vector<ObjectResult> results =
      estimateFrame(frame_, objects, PipelineParams{}, placing);
  const InstancePose& block = results[0].estimate.best();
  EXPECT_GT(block.evidence.explained, 0.1f);
  EXPECT_LE(block.evidence.explained, 0.5f);
  EXPECT_FLOAT_EQ(block.confidence, confidence.confidence(block.evidence));
  EXPECT_LT(block.confidence, alone);
  // The twin holds the pixels both confirm; only its splats' fringe off both maps ties.
  EXPECT_LT(results[1].estimate.best().evidence.explained, block.evidence.explained);
}

// Maps from depth alone mark every region of an object's size alike: the frame loop and the
// tracker judge their poses by the depth_alone coefficients, other maps' by the inherited ones.
TEST_F(EstimatorTest, MapsFromDepthAloneAreJudgedByTheirOwnCoefficients) {
  PipelineParams pipeline;
  pipeline.confidence.depth_alone.intercept += 1;  // the defaults are the maps' coefficients
  Estimator estimator(pipeline, ModelCache(test::scratchDir("estimator_cache")));
  estimator.addObject("block", model_file_);
  const std::vector<FrameObject> objects = {{"block", estimator.model("block").get()}};
  const ConfidenceParams& params = pipeline.confidence;
  const ConfidenceModel& named = params;
  for (const bool maps_name_objects : {true, false}) {
    frame_.maps_name_objects = maps_name_objects;
    const ConfidenceModel& used = maps_name_objects ? named : params.depth_alone;
    const ConfidenceModel& other = maps_name_objects ? params.depth_alone : named;
    const InstancePose detected = estimator.estimate(frame_, "block").best();
    EXPECT_FLOAT_EQ(detected.confidence, used.confidence(detected.evidence)) << maps_name_objects;
    EXPECT_GT(std::abs(detected.confidence - other.confidence(detected.evidence)), 1e-4)
        << maps_name_objects;
    FrameTracker tracker{TrackingParams{}};
    const FrameTracking tracked = tracker.track(frame_, objects, pipeline, 0.0);
    ASSERT_EQ(tracked.objects.size(), 1u);
    const InstancePose& followed = tracked.objects[0].result.estimate.best();
    EXPECT_FLOAT_EQ(followed.confidence, used.confidence(followed.evidence)) << maps_name_objects;
  }
}

}  // namespace
}  // namespace stocs
