#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "stocs/segmentation/colour_boundaries.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

// Two red boxes packed side by side with a 2 px dark gap, on a grey table; the right box has
// a small dark print that does not cross it.
cv::Mat packedBoxes() {
  cv::Mat bgr(120, 160, CV_8UC3, cv::Scalar(150, 160, 165));
  cv::rectangle(bgr, cv::Rect(20, 30, 120, 60), cv::Scalar(40, 50, 200), cv::FILLED);
  cv::rectangle(bgr, cv::Rect(79, 30, 2, 60), cv::Scalar(20, 25, 90), cv::FILLED);
  cv::putText(bgr, "ab", {95, 65}, cv::FONT_HERSHEY_PLAIN, 1.0, cv::Scalar(20, 20, 20));
  return bgr;
}

/// A map certain of the object everywhere.
cv::Mat certain(cv::Size size) {
  return cv::Mat(size, CV_32FC1, cv::Scalar(1.0));
}

TEST(ColourBoundariesTest, TheGapAndTheOutlineAreBoundariesTheFacesInterior) {
  const cv::Mat map = colourBoundaryMap(packedBoxes(), certain({160, 120}), ColourBoundaryParams());
  ASSERT_EQ(map.type(), CV_8UC1);
  ASSERT_EQ(map.size(), cv::Size(160, 120));
  for (int v = 35; v < 85; ++v) EXPECT_EQ(map.at<uint8_t>(v, 80), 0) << "gap at row " << v;
  // The boxes' outline against the table (Canny puts it on one side of the step or the other).
  EXPECT_TRUE(map.at<uint8_t>(29, 60) == 0 || map.at<uint8_t>(30, 60) == 0);
  EXPECT_EQ(map.at<uint8_t>(50, 40), 255);  // inside the left box
  EXPECT_EQ(map.at<uint8_t>(5, 5), 255);    // the table
  // The gap splits the two faces; the print leaves the right face in one piece around it.
  cv::Mat labels;
  cv::connectedComponents(map, labels, 4);
  EXPECT_NE(labels.at<int>(50, 40), labels.at<int>(50, 120));
  EXPECT_EQ(labels.at<int>(40, 120), labels.at<int>(80, 120));
}

TEST(ColourBoundariesTest, AUniformImageHasNoneWhereTheMapHoldsTheObject) {
  const cv::Mat bgr(60, 80, CV_8UC3, cv::Scalar(10, 200, 90));
  EXPECT_EQ(cv::countNonZero(colourBoundaryMap(bgr, certain(bgr.size()), ColourBoundaryParams())),
            60 * 80);
  // Two objects whose gap the colour does not show, meeting a wall the map gives a low
  // probability: the map's outline closes the regions the colour's boundary leaves open.
  cv::Mat bgr2 = bgr.clone();
  bgr2.col(40).setTo(cv::Scalar(0, 0, 0));
  bgr2(cv::Rect(40, 50, 1, 10)).setTo(cv::Scalar(10, 200, 90));  // the gap fades at its far end
  cv::Mat probability = certain(bgr.size());
  probability.rowRange(50, 60) = 0.3f;  // the wall
  cv::Mat labels;
  cv::connectedComponents(colourBoundaryMap(bgr2, probability, ColourBoundaryParams()), labels, 4);
  EXPECT_NE(labels.at<int>(20, 10), labels.at<int>(20, 70));
  EXPECT_EQ(labels.at<int>(55, 10), 0);  // the wall is boundary
  ColourBoundaryParams through_the_wall;
  through_the_wall.min_probability = 0;
  cv::connectedComponents(colourBoundaryMap(bgr2, probability, through_the_wall), labels, 4);
  EXPECT_EQ(labels.at<int>(20, 10), labels.at<int>(20, 70));
}

TEST(ColourBoundariesTest, AppliesOnlyToSearchesForSeveralInstances) {
  ColourBoundaryParams p;
  EXPECT_FALSE(p.appliesTo(1));
  EXPECT_TRUE(p.appliesTo(8));
  p.enabled = false;
  EXPECT_FALSE(p.appliesTo(8));
}

TEST(ColourBoundariesTest, RejectsOtherImagesAndParameters) {
  const ColourBoundaryParams d;
  EXPECT_THROW(colourBoundaryMap(cv::Mat(), certain({4, 4}), d), InputError);
  EXPECT_THROW(colourBoundaryMap(cv::Mat(4, 4, CV_8UC1, cv::Scalar(0)), certain({4, 4}), d),
               InputError);
  const cv::Mat bgr(4, 4, CV_8UC3, cv::Scalar(0, 0, 0));
  EXPECT_THROW(colourBoundaryMap(bgr, certain({5, 4}), d), InputError);
  EXPECT_THROW(colourBoundaryMap(bgr, cv::Mat(4, 4, CV_8UC1, cv::Scalar(1)), d), InputError);
  ColourBoundaryParams p;
  p.line_width = 1;
  EXPECT_THROW(p.validate(), InputError);
  p = ColourBoundaryParams();
  p.min_instances = 0;
  EXPECT_THROW(p.validate(), InputError);
  p = ColourBoundaryParams();
  p.min_probability = 1.5f;
  EXPECT_THROW(p.validate(), InputError);
}

}  // namespace
}  // namespace stocs
