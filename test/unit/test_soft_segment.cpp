// Depth to organized cloud, probability images, and the soft segment of eqs. (1)-(3).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <opencv2/core.hpp>
#include <string>

#include "stocs/estimation/stages/soft_segment.h"
#include "stocs/geometry/normals.h"
#include "stocs/geometry/organized_cloud.h"
#include "stocs/io/probability_image.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

CameraIntrinsics smallCamera() {
  CameraIntrinsics k;
  k.fx = 120;
  k.fy = 110;
  k.cx = 49.5;
  k.cy = 39.5;
  k.width = 100;
  k.height = 80;
  return k;
}

TEST(OrganizedCloud, BackProjectsDepth) {
  const CameraIntrinsics k = smallCamera();
  cv::Mat depth(80, 100, CV_16UC1, cv::Scalar(800));
  depth.at<uint16_t>(10, 20) = 0;
  const OrganizedCloud cloud = cloudFromDepth(depth, k, 0.00125);  // 800 units = 1 m
  EXPECT_EQ(cloud.validCount(), 80 * 100 - 1);
  EXPECT_FALSE(cloud.isValid(10 * 100 + 20));
  const Eigen::Vector3f& p = cloud.at(70, 5);
  EXPECT_NEAR(p.z(), 1.0f, 1e-6f);
  EXPECT_NEAR(p.x(), (70 - 49.5f) / 120, 1e-6f);
  EXPECT_NEAR(p.y(), (5 - 39.5f) / 110, 1e-6f);
  cv::Mat metres(80, 100, CV_32FC1, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  EXPECT_EQ(cloudFromDepth(metres, k, 1.0).validCount(), 0);
}

TEST(OrganizedCloud, RejectsWrongTypesAndSizes) {
  const CameraIntrinsics k = smallCamera();
  EXPECT_THROW(cloudFromDepth(cv::Mat(80, 100, CV_8UC1, cv::Scalar(1)), k, 1.0), InputError);
  EXPECT_THROW(cloudFromDepth(cv::Mat(80, 99, CV_16UC1, cv::Scalar(1)), k, 1.0), InputError);
  EXPECT_THROW(cloudFromDepth(cv::Mat(80, 100, CV_16UC1, cv::Scalar(1)), k, 0.0), InputError);
  EXPECT_THROW(cloudFromDepth(cv::Mat(), k, 1.0), InputError);
}

TEST(OrganizedCloud, IntrinsicsAreRecoveredFromTheCloud) {
  const CameraIntrinsics k = smallCamera();
  cv::Mat depth(80, 100, CV_32FC1);
  for (int v = 0; v < 80; ++v) {
    for (int u = 0; u < 100; ++u)
      depth.at<float>(v, u) = 0.8f + 0.002f * u + 0.001f * v;  // a slanted plane
  }
  const CameraIntrinsics r = intrinsicsFromCloud(cloudFromDepth(depth, k, 1.0));
  EXPECT_NEAR(r.fx, k.fx, 1e-2);
  EXPECT_NEAR(r.fy, k.fy, 1e-2);
  EXPECT_NEAR(r.cx, k.cx, 1e-2);
  EXPECT_NEAR(r.cy, k.cy, 1e-2);
  EXPECT_THROW(intrinsicsFromCloud(OrganizedCloud(100, 80)), InputError);
}

TEST(OrganizedNormal, TheWindowHoldsAtMostSamplesPerAxisSquared) {
  CameraIntrinsics k = smallCamera();
  k.fx = k.fy = 525;
  // 1 cm at 0.8077 m spans 6.5 pixels: a reach of 7 pixels, which an 8-pixel interval divides
  // into steps of 2 (8 samples per axis), not 1 (15).
  const OrganizedCloud wall =
      cloudFromDepth(cv::Mat(80, 100, CV_32FC1, cv::Scalar(0.8077)), k, 1.0);
  OrganizedNormalParams params;
  params.min_neighbours = params.samples_per_axis * params.samples_per_axis + 1;
  const int centre = 40 * 100 + 50;
  EXPECT_FALSE(organizedNormal(wall, centre, 525, params).allFinite());
  params.min_neighbours = 20;  // the samples within the radius: 32 of the 8 x 8
  const Eigen::Vector3f n = organizedNormal(wall, centre, 525, params);
  ASSERT_TRUE(n.allFinite());
  EXPECT_LT(n.z(), -0.999f);
}

TEST(ProbabilityImage, ConvertsTheUsualEncodings) {
  cv::Mat u16(2, 2, CV_16UC1, cv::Scalar(5000));
  EXPECT_FLOAT_EQ(toProbabilityImage(u16).at<float>(1, 1), 0.5f);
  EXPECT_FLOAT_EQ(toProbabilityImage(u16, 5000).at<float>(0, 0), 1.0f);
  // Float rounding just outside [0, 1] is clamped, in every lane of a wide row.
  cv::Mat rounded(1, 37, CV_32FC1, cv::Scalar(-1e-4));
  rounded(cv::Rect(18, 0, 19, 1)) = 1.0001;
  const cv::Mat clamped = toProbabilityImage(rounded);
  for (int u = 0; u < 37; ++u) EXPECT_EQ(clamped.at<float>(0, u), u < 18 ? 0.0f : 1.0f) << u;
  cv::Mat u8(2, 2, CV_8UC1, cv::Scalar(255));
  EXPECT_FLOAT_EQ(toProbabilityImage(u8).at<float>(0, 1), 1.0f);
  cv::Mat f32(2, 2, CV_32FC1, cv::Scalar(0.25));
  EXPECT_FLOAT_EQ(toProbabilityImage(f32).at<float>(1, 0), 0.25f);
}

TEST(ProbabilityImage, RejectsBadImagesWithTheReason) {
  EXPECT_THROW(toProbabilityImage(cv::Mat()), InputError);
  EXPECT_THROW(toProbabilityImage(cv::Mat(2, 2, CV_8UC3, cv::Scalar(1, 1, 1))), InputError);
  EXPECT_THROW(toProbabilityImage(cv::Mat(2, 2, CV_16SC1, cv::Scalar(1))), InputError);
  cv::Mat over(2, 2, CV_32FC1, cv::Scalar(0.5));
  over.at<float>(1, 0) = 1.5f;
  try {
    toProbabilityImage(over);
    FAIL() << "no error for a value above 1";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("(u=0, v=1)"), std::string::npos) << e.what();
  }
  cv::Mat nan(2, 2, CV_32FC1, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  EXPECT_THROW(toProbabilityImage(nan), InputError);
  // Rows wider than the vector loops' lanes: a bad value in their body and in their tail.
  for (const int u : {21, 36}) {
    cv::Mat wide(3, 37, CV_32FC1, cv::Scalar(0.5));
    wide.at<float>(2, u) = u == 21 ? -0.5f : std::numeric_limits<float>::quiet_NaN();
    try {
      toProbabilityImage(wide);
      ADD_FAILURE() << "no error for the value at u=" << u;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("(u=" + std::to_string(u) + ", v=2)"), std::string::npos)
          << e.what();
    }
  }
  EXPECT_THROW(toProbabilityImage(cv::Mat(2, 2, CV_16UC1, cv::Scalar(10001))), InputError);
}

class SoftSegmentTest : public ::testing::Test {
 protected:
  void SetUp() override {
    k_ = smallCamera();
    cloud_ = cloudFromDepth(cv::Mat(80, 100, CV_32FC1, cv::Scalar(1.0)), k_, 1.0);  // wall at 1 m
    prob_ = cv::Mat(80, 100, CV_32FC1, cv::Scalar(0.05));                           // below epsilon
    prob_(cv::Rect(50, 0, 50, 80)) = 0.8;
    prob_(cv::Rect(40, 0, 10, 80)) = 0.1;  // exactly epsilon: excluded (strictly greater is kept)
  }
  CameraIntrinsics k_;
  OrganizedCloud cloud_;
  cv::Mat prob_;
};

TEST_F(SoftSegmentTest, KeepsPixelsAboveEpsilonWithNormalisedProbabilities) {
  SoftSegmentParams params;
  params.voxel_size = 0;
  const SoftSegment s = buildSoftSegment(cloud_, prob_, static_cast<float>(k_.fx), params);
  ASSERT_EQ(s.size(), 50u * 80);
  EXPECT_NEAR(std::accumulate(s.probability.begin(), s.probability.end(), 0.0), 1.0, 1e-5);
  for (size_t i = 0; i < s.size(); ++i) {
    EXPECT_GE(s.pixel[i] % 100, 50);
    EXPECT_FLOAT_EQ(s.confidence[i], 0.8f);
    EXPECT_LT(s.normals[i].z(), -0.999f) << "wall normal must face the camera";
  }
}

TEST_F(SoftSegmentTest, IsolatedPixelsAnywhereInARowAreKept) {
  // Single pixels above epsilon on background, at block edges and in a row's tail (background
  // blocks are skipped as a whole, so a block with one pixel above epsilon must still be seen).
  cv::Mat prob(80, 100, CV_32FC1, cv::Scalar(0.0));
  const std::vector<int> columns = {0, 15, 16, 31, 47, 63, 95, 96, 99};
  for (size_t k = 0; k < columns.size(); ++k)
    prob.at<float>(static_cast<int>(10 + 5 * k), columns[k]) = 0.7f;
  SoftSegmentParams params;
  params.voxel_size = 0;
  params.normals.min_neighbours = 3;
  const SoftSegment s = buildSoftSegment(cloud_, prob, static_cast<float>(k_.fx), params);
  ASSERT_EQ(s.size(), columns.size());
  for (size_t k = 0; k < columns.size(); ++k) {
    EXPECT_EQ(s.pixel[k], static_cast<int>(10 + 5 * k) * 100 + columns[k]);
  }
}

TEST_F(SoftSegmentTest, ThreadsDoNotChangeTheSegment) {
  SoftSegmentParams params;
  params.voxel_size = 0.01f;
  const SoftSegment one = buildSoftSegment(cloud_, prob_, static_cast<float>(k_.fx), params, 1);
  const SoftSegment three = buildSoftSegment(cloud_, prob_, static_cast<float>(k_.fx), params, 3);
  ASSERT_GT(one.size(), 100u);
  EXPECT_EQ(one.pixel, three.pixel);
  EXPECT_EQ(one.points, three.points);
  EXPECT_EQ(one.normals, three.normals);
  EXPECT_EQ(one.probability, three.probability);
}

TEST_F(SoftSegmentTest, ARegionOfInterestKeepsThePixelsInsideIt) {
  SoftSegmentParams params;
  params.voxel_size = 0;
  const float f = static_cast<float>(k_.fx);
  const SoftSegment all = buildSoftSegment(cloud_, prob_, f, params);
  const SoftSegment whole =
      buildSoftSegment(cloud_, prob_, f, params, 1, cv::Rect(-5, -5, 200, 200));
  EXPECT_EQ(whole.pixel, all.pixel);
  EXPECT_EQ(whole.points, all.points);
  const cv::Rect roi(43, 17, 30, 21);  // across the segment's left edge, not on a chunk's rows
  const SoftSegment part = buildSoftSegment(cloud_, prob_, f, params, 2, roi);
  std::vector<int> inside;
  for (int pixel : all.pixel) {
    if (roi.contains(cv::Point(pixel % 100, pixel / 100))) inside.push_back(pixel);
  }
  ASSERT_EQ(inside.size(), 23u * 21);
  EXPECT_EQ(part.pixel, inside);
  EXPECT_TRUE(buildSoftSegment(cloud_, prob_, f, params, 1, cv::Rect(200, 0, 10, 10)).empty());
}

TEST_F(SoftSegmentTest, VoxelsAverageTheirPixels) {
  prob_(cv::Rect(50, 0, 50, 40)) = 0.4;
  SoftSegmentParams params;
  params.voxel_size = 0.05f;
  const SoftSegment s = buildSoftSegment(cloud_, prob_, static_cast<float>(k_.fx), params);
  // The kept half spans 50 px / 120 px/m = 0.42 m by 80 px / 110 px/m = 0.73 m: about 9 x 15 voxels
  // of 5 cm instead of 4000 pixels.
  ASSERT_GT(s.size(), 110u);
  EXPECT_LT(s.size(), 180u);
  for (size_t i = 0; i < s.size(); ++i) {
    EXPECT_NEAR(s.points[i].z(), 1.0f, 1e-5f);
    EXPECT_GT(s.confidence[i], 0.39f);
    EXPECT_LT(s.confidence[i], 0.81f);
    // The representative pixel lies in the voxel.
    EXPECT_LT((cloud_.points[s.pixel[i]] - s.points[i]).norm(), 0.05f * std::sqrt(3.0f));
  }
  EXPECT_NEAR(std::accumulate(s.probability.begin(), s.probability.end(), 0.0), 1.0, 1e-5);
}

TEST_F(SoftSegmentTest, VoxelsMatchAPlainGroupingOnARoughSurface) {
  // Bumps and a tilt make voxels of irregular pixel shapes, so one voxel's pixels come back after
  // others in a row and in later rows; gaps below epsilon break runs.
  cv::Mat depth(80, 100, CV_32FC1);
  cv::RNG rng(7);
  for (int v = 0; v < 80; ++v) {
    for (int u = 0; u < 100; ++u) {
      depth.at<float>(v, u) =
          static_cast<float>(0.8 + 0.002 * u + 0.01 * std::sin(u * 0.7) * std::cos(v * 0.4) +
                             rng.uniform(-0.002, 0.002));
      prob_.at<float>(v, u) = static_cast<float>(rng.uniform(0.0, 1.0));
    }
  }
  const OrganizedCloud cloud = cloudFromDepth(depth, k_, 1.0);
  SoftSegmentParams params;
  params.voxel_size = 0.02f;

  // The same grouping written plainly: voxels by std::floor, in order of their first pixel, sums
  // in pixel order, the representative the first pixel nearest the centroid.
  struct Group {
    Eigen::Vector3f sum = Eigen::Vector3f::Zero();
    double probability = 0;
    int count = 0, representative = -1;
  };
  std::map<std::array<int, 3>, size_t> index;
  std::vector<Group> groups;
  std::vector<std::pair<int, size_t>> members;
  for (int i = 0; i < 80 * 100; ++i) {
    const float p = prob_.at<float>(i / 100, i % 100);
    if (!(p > params.min_probability)) continue;
    const Eigen::Vector3f& x = cloud.points[i];
    const std::array<int, 3> cell = {static_cast<int>(std::floor(x.x() / params.voxel_size)),
                                     static_cast<int>(std::floor(x.y() / params.voxel_size)),
                                     static_cast<int>(std::floor(x.z() / params.voxel_size))};
    const size_t g = index.try_emplace(cell, groups.size()).first->second;
    if (g == groups.size()) groups.emplace_back();
    groups[g].sum += x;
    groups[g].probability += p;
    ++groups[g].count;
    members.emplace_back(i, g);
  }
  std::vector<float> best(groups.size(), std::numeric_limits<float>::max());
  for (const auto& [i, g] : members) {
    const float d2 =
        (cloud.points[i] - groups[g].sum / static_cast<float>(groups[g].count)).squaredNorm();
    if (d2 < best[g]) {
      best[g] = d2;
      groups[g].representative = i;
    }
  }
  ASSERT_GT(groups.size(), 300u);
  ASSERT_LT(groups.size(), 4000u) << "voxels should hold several pixels";
  // The segment keeps the groups whose representative has a normal (a few at the image border
  // have none), in the same order and with the same sums, whatever the number of threads it is
  // scanned on (the 80 rows make 5 chunks of 16, and voxels of about 3 pixels span their borders:
  // their sums go on across chunks).
  for (int threads : {1, 2, 3}) {
    const SoftSegment s =
        buildSoftSegment(cloud, prob_, static_cast<float>(k_.fx), params, threads);
    size_t j = 0, without_normal = 0;
    for (const Group& group : groups) {
      if (j == s.size() || s.pixel[j] != group.representative) {
        ++without_normal;
        continue;
      }
      EXPECT_EQ(s.points[j], group.sum / static_cast<float>(group.count)) << j;
      EXPECT_EQ(s.confidence[j], static_cast<float>(group.probability / group.count)) << j;
      ++j;
    }
    EXPECT_EQ(j, s.size()) << threads << " threads";
    EXPECT_LT(without_normal, groups.size() / 50) << threads << " threads";
  }
}

TEST_F(SoftSegmentTest, PixelsWithoutDepthAreLeftOutAndEmptyIsFine) {
  OrganizedCloud holes = cloud_;
  for (int v = 0; v < 80; ++v) {
    for (int u = 50; u < 100; ++u)
      holes.points[v * 100 + u].setConstant(std::numeric_limits<float>::quiet_NaN());
  }
  const SoftSegment s =
      buildSoftSegment(holes, prob_, static_cast<float>(k_.fx), SoftSegmentParams{});
  EXPECT_TRUE(s.empty());
}

TEST_F(SoftSegmentTest, MismatchesAndBadParametersAreErrors) {
  EXPECT_THROW(buildSoftSegment(cloud_, cv::Mat(80, 99, CV_32FC1, cv::Scalar(0.5)), 120,
                                SoftSegmentParams{}),
               InputError);
  EXPECT_THROW(
      buildSoftSegment(cloud_, cv::Mat(80, 100, CV_16UC1, cv::Scalar(1)), 120, SoftSegmentParams{}),
      InputError);
  EXPECT_THROW(buildSoftSegment(cloud_, prob_, 0, SoftSegmentParams{}), InputError);
  SoftSegmentParams bad;
  bad.min_probability = 1.0f;
  EXPECT_THROW(buildSoftSegment(cloud_, prob_, 120, bad), InputError);
  for (float samples : {0.5f, -1.0f, 101.0f, std::numeric_limits<float>::quiet_NaN()}) {
    SoftSegmentParams thin;
    thin.samples_per_voxel = samples;
    EXPECT_THROW(buildSoftSegment(cloud_, prob_, 120, thin), InputError) << samples;
  }
}

TEST_F(SoftSegmentTest, TheScanThinsWhereAVoxelSpansManyPixels) {
  // Voxels of 5 cm on the wall 1 m away span 6 x 5.5 pixels: two samples across take every 3rd
  // row and column.
  SoftSegmentParams params;
  params.voxel_size = 0.05f;
  const float focal = static_cast<float>(k_.fx);
  ASSERT_EQ(segmentPixelStride(cloud_, prob_, focal, params), 3);
  const SoftSegment thinned = buildSoftSegment(cloud_, prob_, focal, params);
  params.samples_per_voxel = 0;
  ASSERT_EQ(segmentPixelStride(cloud_, prob_, focal, params), 1);
  const SoftSegment every = buildSoftSegment(cloud_, prob_, focal, params);
  // Every voxel but a sliver at the segment's edge has samples; only the lattice was read.
  EXPECT_LE(thinned.size(), every.size());
  EXPECT_GE(thinned.size(), every.size() * 9 / 10);
  auto onLattice = [](int pixel) { return pixel % 100 % 3 == 0 && pixel / 100 % 3 == 0; };
  EXPECT_TRUE(std::all_of(thinned.pixel.begin(), thinned.pixel.end(), onLattice));
  EXPECT_FALSE(std::all_of(every.pixel.begin(), every.pixel.end(), onLattice));
  for (size_t i = 0; i < thinned.size(); ++i) {
    EXPECT_GT(thinned.confidence[i], 0.1f);
    EXPECT_LT((cloud_.points[thinned.pixel[i]] - thinned.points[i]).norm(),
              0.05f * std::sqrt(2.0f));
  }

  // Voxels of 1 cm span 1.2 pixels: every pixel is read, and the segment is the full scan's.
  params.voxel_size = 0.01f;
  EXPECT_EQ(segmentPixelStride(cloud_, prob_, focal, params), 1);
  const SoftSegment small_every = buildSoftSegment(cloud_, prob_, focal, params);
  params.samples_per_voxel = 2;
  EXPECT_EQ(buildSoftSegment(cloud_, prob_, focal, params).points, small_every.points);
}

TEST_F(SoftSegmentTest, TheFarPixelsOfTheSegmentSetTheStride) {
  // A wall at 0.5 m on the left and at 2 m on the right: 5 cm voxels span 12 and 3 pixels.
  cv::Mat depth(80, 100, CV_32FC1, cv::Scalar(0.5));
  depth(cv::Rect(50, 0, 50, 80)) = 2.0;
  const OrganizedCloud cloud = cloudFromDepth(depth, k_, 1.0);
  SoftSegmentParams params;
  params.voxel_size = 0.05f;
  const float focal = static_cast<float>(k_.fx);
  cv::Mat near_only(80, 100, CV_32FC1, cv::Scalar(0.0));
  near_only(cv::Rect(0, 0, 50, 80)) = 0.9;
  EXPECT_EQ(segmentPixelStride(cloud, near_only, focal, params), 6);
  // Half the segment far: its 90th percentile is the far wall.
  EXPECT_EQ(segmentPixelStride(cloud, cv::Mat(80, 100, CV_32FC1, cv::Scalar(0.9)), focal, params),
            1);
  EXPECT_EQ(segmentPixelStride(cloud, cv::Mat(80, 100, CV_32FC1, cv::Scalar(0.0)), focal, params),
            1);
}

TEST_F(SoftSegmentTest, RegionsComeFromTheBoundaryMap) {
  SoftSegmentParams params;
  params.voxel_size = 0;
  SoftSegment s = buildSoftSegment(cloud_, prob_, static_cast<float>(k_.fx), params);
  cv::Mat boundary(80, 100, CV_8UC1, cv::Scalar(255));
  boundary.col(75) = 0;  // splits the segment into two instances
  labelRegions(s, boundary, 100, 80);
  ASSERT_EQ(s.region.size(), s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    const int u = s.pixel[i] % 100;
    if (u == 75) {
      EXPECT_EQ(s.region[i], -1);
    } else {
      EXPECT_GE(s.region[i], 1);
      const int left_region = s.region[std::find_if(s.pixel.begin(), s.pixel.end(),
                                                    [](int p) { return p % 100 == 60; }) -
                                       s.pixel.begin()];
      EXPECT_EQ(s.region[i] == left_region, u < 75);
    }
  }
  EXPECT_THROW(labelRegions(s, cv::Mat(80, 100, CV_16UC1, cv::Scalar(0)), 100, 80), InputError);
  EXPECT_THROW(labelRegions(s, cv::Mat(81, 100, CV_8UC1, cv::Scalar(0)), 100, 80), InputError);
}

}  // namespace
}  // namespace stocs
