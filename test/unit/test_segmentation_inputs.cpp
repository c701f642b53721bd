// Labels, instance masks and 2D boxes turned into soft per-class probability maps.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "stocs/io/segmentation_inputs.h"
#include "test_support.h"

namespace stocs {
namespace {
using test::expectInputError;

const cv::Size kSize(80, 60);

float at(const cv::Mat& m, int u, int v) {
  return m.at<float>(v, u);
}

/// A mask with a filled rectangle.
cv::Mat rectMask(const cv::Rect& r) {
  cv::Mat m(kSize, CV_8UC1, cv::Scalar(0));
  m(r).setTo(255);
  return m;
}

TEST(SegmentationInputs, LabelsGiveTheClassItsPixelsWithASoftBorderAndTheConfidence) {
  SegmentationInputParams params;
  cv::Mat labels(kSize, CV_16UC1, cv::Scalar(0));
  labels(cv::Rect(20, 10, 30, 30)).setTo(7);
  labels(cv::Rect(55, 10, 10, 10)).setTo(3);
  const cv::Mat p = labelProbability(labels, cv::Mat(), 7, params);
  ASSERT_EQ(p.type(), CV_32FC1);
  EXPECT_NEAR(at(p, 35, 25), 1.0f, 1e-3);  // deep inside
  EXPECT_FLOAT_EQ(at(p, 5, 5), 0.0f);      // far outside
  EXPECT_NEAR(at(p, 60, 15), 0.0f, 1e-3);  // another class
  // The outline: the inside pixel is at least the floor and below 1, the outside one is
  // between 0 and one half.
  EXPECT_GE(at(p, 20, 25), params.mask_inside_floor);
  EXPECT_LT(at(p, 20, 25), 1.0f);
  EXPECT_GT(at(p, 19, 25), 0.0f);
  EXPECT_LT(at(p, 19, 25), 0.5f);

  cv::Mat confidence(kSize, CV_8UC1, cv::Scalar(128));
  const cv::Mat c = labelProbability(labels, confidence, 7, params);
  EXPECT_NEAR(at(c, 35, 25), 128.0f / 255.0f, 1e-3);
  EXPECT_FLOAT_EQ(at(c, 19, 25), at(p, 19, 25));  // the border outside keeps the blur
}

TEST(SegmentationInputs, HardEdgesAndFloorsAreParameters) {
  SegmentationInputParams params;
  params.mask_border_px = 0;
  params.mask_outside_floor = 0.1f;
  cv::Mat labels(kSize, CV_8UC1, cv::Scalar(0));
  labels(cv::Rect(20, 10, 30, 30)).setTo(2);
  const cv::Mat p = labelProbability(labels, cv::Mat(), 2, params);
  EXPECT_FLOAT_EQ(at(p, 20, 25), 1.0f);
  EXPECT_FLOAT_EQ(at(p, 19, 25), 0.1f);
  EXPECT_FLOAT_EQ(at(p, 0, 0), 0.1f);
}

TEST(SegmentationInputs, MasksAreWeightedByTheirScoreAndThinPartsKeepTheFloor) {
  SegmentationInputParams params;
  std::vector<InstanceMask> masks = {
      {rectMask(cv::Rect(5, 5, 40, 40)), 5, 0.8f},
      {rectMask(cv::Rect(25, 15, 40, 40)), 5, 0.5f},
      {rectMask(cv::Rect(0, 50, 80, 10)), 9, 1.0f},  // another class
      {rectMask(cv::Rect(70, 0, 1, 40)), 5, 1.0f},   // one pixel wide
  };
  const cv::Mat p = maskProbability(masks, 5, kSize, params);
  EXPECT_NEAR(at(p, 20, 20), 0.8f, 1e-3);
  EXPECT_NEAR(at(p, 35, 30), 0.8f, 1e-3);  // overlap: the larger
  EXPECT_NEAR(at(p, 55, 40), 0.5f, 1e-3);
  EXPECT_FLOAT_EQ(at(p, 5, 57), 0.0f);
  EXPECT_NEAR(at(p, 70, 20), params.mask_inside_floor, 1e-6);
  EXPECT_FLOAT_EQ(at(maskProbability(masks, 4, kSize, params), 20, 20), 0.0f);
  // Without the floor, the blur would leave the one-pixel line below it.
  params.mask_inside_floor = 0;
  EXPECT_LT(at(maskProbability(masks, 5, kSize, params), 70, 20), 0.2f);
}

TEST(SegmentationInputs, BadMasksAndLabelsNameTheProblem) {
  const SegmentationInputParams params;
  std::vector<InstanceMask> masks = {{rectMask(cv::Rect(0, 0, 5, 5)), 1, 1.0f},
                                     {cv::Mat(10, 10, CV_8UC1, cv::Scalar(0)), 2, 1.0f}};
  expectInputError([&] { maskProbability(masks, 1, kSize, params); },
                   "mask 1 (class 2) is 10x10 but the depth image is 80x60");
  masks[1] = {rectMask(cv::Rect(0, 0, 5, 5)), 2, std::numeric_limits<float>::quiet_NaN()};
  expectInputError([&] { maskProbability(masks, 1, kSize, params); },
                   "mask 1 (class 2) has score nan");
  masks[1] = {cv::Mat(kSize, CV_32FC1, cv::Scalar(0)), 2, 1.0f};
  expectInputError([&] { maskProbability(masks, 1, kSize, params); }, "expected one 8-bit");
  expectInputError(
      [&] { labelProbability(cv::Mat(kSize, CV_32FC1, cv::Scalar(0)), cv::Mat(), 1, params); },
      "label image has OpenCV type 5");
  expectInputError(
      [&] {
        labelProbability(cv::Mat(kSize, CV_8UC1, cv::Scalar(0)),
                         cv::Mat(10, 10, CV_8UC1, cv::Scalar(0)), 1, params);
      },
      "confidence image is 10x10 but the label image is 80x60");
}

TEST(SegmentationInputs, BoxesAreASoftPriorFallingOffTowardTheirEdges) {
  SegmentationInputParams params;
  const std::vector<BoxDetection> boxes = {{cv::Rect2f(20, 10, 40, 40), 3, 0.9f},
                                           {cv::Rect2f(70, 50, 30, 30), 3, 0.6f},
                                           {cv::Rect2f(0, 0, 10, 10), 4, 1.0f}};
  const cv::Mat p = boxProbability(boxes, 3, kSize, params);
  EXPECT_FLOAT_EQ(at(p, 40, 30), 0.9f);  // centre
  EXPECT_FLOAT_EQ(at(p, 45, 35), 0.9f);  // within the core
  // Toward the left edge the prior falls to edge_level times the score, and is 0 beyond it.
  EXPECT_LT(at(p, 25, 30), at(p, 30, 30));
  // The edge pixel's centre lies 0.975 half-widths from the box's centre.
  const float fall = (0.975f - params.box_core) / (1.0f - params.box_core);
  EXPECT_NEAR(at(p, 20, 30), 0.9f * (1.0f - (1.0f - params.box_edge_level) * fall), 1e-5);
  EXPECT_FLOAT_EQ(at(p, 19, 30), 0.0f);
  EXPECT_FLOAT_EQ(at(p, 5, 5), 0.0f);  // another class
  EXPECT_GT(at(p, 75, 55), 0.0f);      // a box cut by the image's border
  EXPECT_LE(at(p, 75, 55), 0.6f);
  // Boxes far outside the image, or larger than an int, draw nothing or cover it.
  const std::vector<BoxDetection> far = {{cv::Rect2f(1e30f, -1e30f, 5, 5), 3, 1.0f},
                                         {cv::Rect2f(-1e20f, -1e20f, 3e20f, 3e20f), 4, 0.5f}};
  EXPECT_EQ(cv::countNonZero(boxProbability(far, 3, kSize, params)), 0);
  EXPECT_EQ(cv::countNonZero(boxProbability(far, 4, kSize, params)), kSize.area());
}

TEST(SegmentationInputs, MalformedBoxesNameTheBox) {
  const SegmentationInputParams params;
  std::vector<BoxDetection> boxes = {{cv::Rect2f(0, 0, 5, 5), 1, 1.0f},
                                     {cv::Rect2f(0, 0, 0, 5), 2, 1.0f}};
  expectInputError([&] { boxProbability(boxes, 1, kSize, params); },
                   "box 1 (class 2) is x 0 y 0 width 0 height 5");
  boxes[1].box = cv::Rect2f(std::numeric_limits<float>::infinity(), 0, 5, 5);
  expectInputError([&] { boxProbability(boxes, 1, kSize, params); }, "box 1 (class 2)");
  boxes[1] = {cv::Rect2f(0, 0, 5, 5), 2, -0.1f};
  expectInputError([&] { boxProbability(boxes, 1, kSize, params); }, "has score -0.1");
}

TEST(SegmentationInputs, ParametersOutOfRangeAreRefused) {
  SegmentationInputParams params;
  params.box_core = 1.0f;
  expectInputError([&] { params.validate(); }, "box_core");
  params = {};
  params.mask_inside_floor = 1.5f;
  expectInputError([&] { params.validate(); }, "mask_inside_floor");
}

}  // namespace
}  // namespace stocs
