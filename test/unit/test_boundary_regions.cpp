// BoundaryRegions against cv::connectedComponents (4-connectivity), which defines the regions: the
// same region number at every pixel, on hand-made shapes, random maps and the real boundary maps.
#include "stocs/estimation/stages/boundary_regions.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "stocs/io/bop_dataset.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

/// Number of pixels where the two labellings differ (region numbers included).
int differences(const cv::Mat& boundary_map) {
  cv::Mat labels;
  const int components = cv::connectedComponents(boundary_map >= 128, labels, 4, CV_32S);
  const BoundaryRegions regions(boundary_map);
  int differ = regions.count() != components - 1;
  for (int v = 0; v < boundary_map.rows; ++v) {
    for (int u = 0; u < boundary_map.cols; ++u) differ += regions.at(u, v) != labels.at<int>(v, u);
  }
  return differ;
}

TEST(BoundaryRegions, AUShapeIsOneRegionWhoseArmsMeetAtTheBottom) {
  cv::Mat map(6, 11, CV_8UC1, cv::Scalar(0));
  map(cv::Rect(1, 0, 2, 6)) = 255;  // left arm, from the top row
  map(cv::Rect(8, 0, 2, 6)) = 255;  // right arm
  map(cv::Rect(1, 5, 9, 1)) = 255;  // the bottom joins them
  map.at<uint8_t>(0, 5) = 200;      // a lone pixel between the arms, after the left arm's first
  const BoundaryRegions regions(map);
  EXPECT_EQ(regions.count(), 2);
  EXPECT_EQ(regions.at(1, 0), 1);
  EXPECT_EQ(regions.at(9, 0), 1);
  EXPECT_EQ(regions.at(5, 5), 1);
  EXPECT_EQ(regions.at(5, 0), 2);
  EXPECT_EQ(regions.at(0, 0), 0);
  EXPECT_EQ(regions.at(5, 3), 0);
  EXPECT_EQ(differences(map), 0);
}

TEST(BoundaryRegions, DiagonalNeighboursAreSeparateRegions) {
  cv::Mat map(2, 2, CV_8UC1, cv::Scalar(0));
  map.at<uint8_t>(0, 0) = map.at<uint8_t>(1, 1) = 255;
  const BoundaryRegions regions(map);
  EXPECT_EQ(regions.count(), 2);
  EXPECT_EQ(regions.at(0, 0), 1);
  EXPECT_EQ(regions.at(1, 1), 2);
}

TEST(BoundaryRegions, UniformMapsAndTheThreshold) {
  EXPECT_EQ(BoundaryRegions(cv::Mat(5, 17, CV_8UC1, cv::Scalar(255))).count(), 1);
  EXPECT_EQ(BoundaryRegions(cv::Mat(5, 17, CV_8UC1, cv::Scalar(128))).count(), 1);
  EXPECT_EQ(BoundaryRegions(cv::Mat(5, 17, CV_8UC1, cv::Scalar(127))).count(), 0);
  EXPECT_EQ(BoundaryRegions(cv::Mat(5, 17, CV_8UC1, cv::Scalar(127))).at(16, 4), 0);
}

TEST(BoundaryRegions, RandomMapsMatchOpenCv) {
  std::mt19937 rng(7);
  // Widths off and on multiples of the 8-pixel step; interior shares from sparse specks to a
  // few cuts through a filled image, and blocky maps with long runs.
  const cv::Size sizes[] = {{1, 1}, {7, 3}, {8, 8}, {37, 23}, {64, 40}, {101, 67}};
  for (const cv::Size size : sizes) {
    for (const double interior : {0.2, 0.5, 0.6, 0.9}) {
      for (const int block : {1, 3, 9}) {
        cv::Mat small((size.height + block - 1) / block, (size.width + block - 1) / block, CV_8UC1);
        std::bernoulli_distribution in(interior);
        for (int v = 0; v < small.rows; ++v) {
          for (int u = 0; u < small.cols; ++u) small.at<uint8_t>(v, u) = in(rng) ? 255 : 0;
        }
        cv::Mat map;
        cv::resize(small, map, {small.cols * block, small.rows * block}, 0, 0, cv::INTER_NEAREST);
        map = map(cv::Rect(0, 0, size.width, size.height)).clone();
        EXPECT_EQ(differences(map), 0)
            << size.width << "x" << size.height << " interior " << interior << " block " << block;
      }
    }
  }
}

TEST(BoundaryRegions, RealBoundaryMapsMatchOpenCv) {
  STOCS_REQUIRE_DATASETS(root);
  const BopDataset ds(root / "rutgers-packed");
  const cv::Mat map = ds.loadBoundary(0, 0);
  ASSERT_FALSE(map.empty());
  EXPECT_GT(BoundaryRegions(map).count(), 10);
  EXPECT_EQ(differences(map), 0);
}

TEST(BoundaryRegions, RejectsOtherImageTypes) {
  EXPECT_THROW(BoundaryRegions(cv::Mat(4, 4, CV_16UC1, cv::Scalar(0))), InputError);
  EXPECT_THROW(BoundaryRegions(cv::Mat(4, 4, CV_8UC3, cv::Scalar(0, 0, 0))), InputError);
  EXPECT_THROW(BoundaryRegions(cv::Mat()), InputError);
}

}  // namespace
}  // namespace stocs
