// BOP dataset reading, results files, and the errors for malformed inputs.
#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "stocs/io/bop_dataset.h"
#include "stocs/io/bop_results.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(BopDataset, ReadsASyntheticDataset) {
  const auto root = test::scratchDir("bop_read");
  const Eigen::Isometry3f pose = test::writeSyntheticBopDataset(root);
  const BopDataset ds(root);
  EXPECT_EQ(ds.sceneIds(), std::vector<int>{0});
  const auto cams = ds.sceneCameras(0);
  ASSERT_EQ(cams.count(0), 1u);
  EXPECT_DOUBLE_EQ(cams.at(0).K(0, 2), 160);
  EXPECT_DOUBLE_EQ(cams.at(0).depth_scale, 0.1);
  const auto gt = ds.sceneGroundTruth(0);
  ASSERT_EQ(gt.at(0).size(), 1u);
  EXPECT_EQ(gt.at(0)[0].obj_id, 1);
  EXPECT_NEAR(gt.at(0)[0].t_mm.z(), pose.translation().z() * 1000, 1e-3);
  EXPECT_TRUE(gt.at(0)[0].R.isApprox(pose.linear().cast<double>(), 1e-5));
  EXPECT_GT(ds.modelsInfo().at(1).diameter_mm, 100);
  EXPECT_FALSE(ds.modelsInfo().at(1).symmetric());
  EXPECT_EQ(ds.loadDepth(0, 0).type(), CV_16UC1);
  EXPECT_EQ(ds.loadProbability(0, 0, 1).type(), CV_32FC1);
  EXPECT_TRUE(ds.loadBoundary(0, 0).empty());
  EXPECT_TRUE(ds.loadColour(0, 0, {320, 240}).empty());
}

TEST(BopDataset, ReadsTheColourImageOfAFrameAndNamesOneThatDoesNotFit) {
  const auto root = test::scratchDir("bop_colour");
  test::writeSyntheticBopDataset(root);
  const BopDataset ds(root);
  std::filesystem::create_directories(root / "test" / "000000" / "rgb");
  const cv::Mat bgr(240, 320, CV_8UC3, cv::Scalar(10, 20, 30));
  ASSERT_TRUE(cv::imwrite(ds.rgbPath(0, 0).replace_extension(".jpg").string(), bgr));
  const cv::Mat read = ds.loadColour(0, 0, {320, 240});
  ASSERT_EQ(read.type(), CV_8UC3);
  EXPECT_NEAR(cv::mean(read)[2], 30, 2);
  EXPECT_NE(errorOf([&] {
              ds.loadColour(0, 0, {640, 480});
            }).find("000000.jpg: colour image is 320x240 but the depth image is 640x480"),
            std::string::npos);
  std::ofstream(ds.rgbPath(0, 0)) << "not a png";  // .png comes first
  EXPECT_NE(errorOf([&] {
              ds.loadColour(0, 0, {320, 240});
            }).find("000000.png: not a readable"),
            std::string::npos);
}

TEST(BopDataset, MalformedFilesNameTheFileAndProblem) {
  const auto root = test::scratchDir("bop_bad");
  test::writeSyntheticBopDataset(root);
  const BopDataset ds(root);
  const auto scene = root / "test" / "000000";
  std::ofstream(scene / "scene_gt.json") << "{\"0\": [ {\"cam_R_m2c\": [1, 0, 0]} ]";
  EXPECT_NE(errorOf([&] { ds.sceneGroundTruth(0); }).find("scene_gt.json: invalid JSON"),
            std::string::npos);
  std::ofstream(scene / "scene_gt.json")
      << R"({"0": [{"cam_R_m2c": [1, 0, 0], "cam_t_m2c": [0, 0, 1], "obj_id": 1}]})";
  EXPECT_NE(
      errorOf([&] { ds.sceneGroundTruth(0); }).find("'cam_R_m2c' must be an array of 9 numbers"),
      std::string::npos);
  std::ofstream(scene / "scene_camera.json") << R"({"x": {"cam_K": [1, 0, 0, 0, 1, 0, 0, 0, 1]}})";
  EXPECT_NE(errorOf([&] { ds.sceneCameras(0); }).find("key 'x'"), std::string::npos);
  std::ofstream(scene / "scene_camera.json") << R"({"0": {"cam_K": [0, 0, 0, 0, 1, 0, 0, 0, 1]}})";
  EXPECT_NE(errorOf([&] { ds.sceneCameras(0); }).find("non-positive"), std::string::npos);
  std::filesystem::remove(scene / "depth" / "000000.png");
  EXPECT_NE(errorOf([&] { ds.loadDepth(0, 0); }).find("000000.png: missing"), std::string::npos);
  std::ofstream(scene / "prob" / "000000_000001.png") << "not a png";
  EXPECT_NE(errorOf([&] { ds.loadProbability(0, 0, 1); }).find("000000_000001.png"),
            std::string::npos);
  EXPECT_NE(errorOf([] { BopDataset("/nonexistent/dataset"); }).find("not a folder"),
            std::string::npos);
}

TEST(BopResults, RoundTripAndMalformedRows) {
  const auto dir = test::scratchDir("bop_results");
  BopResult r;
  r.scene_id = 3;
  r.im_id = 17;
  r.obj_id = 6;
  r.score = 0.125;
  r.R = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  r.t_mm = Eigen::Vector3d(12.5, -3.25, 812.0);
  r.time = 0.0421;
  writeBopResults(dir / "r.csv", {r, r});
  const std::vector<BopResult> back = readBopResults(dir / "r.csv");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].scene_id, 3);
  EXPECT_EQ(back[1].im_id, 17);
  EXPECT_EQ(back[1].obj_id, 6);
  EXPECT_NEAR(back[1].score, 0.125, 1e-9);
  EXPECT_TRUE(back[1].R.isApprox(r.R, 1e-8));
  EXPECT_TRUE(back[1].t_mm.isApprox(r.t_mm, 1e-6));
  EXPECT_NEAR(back[1].time, 0.0421, 1e-9);

  std::ofstream(dir / "bad.csv")
      << "scene_id,im_id,obj_id,score,R,t,time\n1,2,3,0.5,1 0 0 0 1 0 0 0,0 0 0,1\n";
  EXPECT_NE(
      errorOf([&] { readBopResults(dir / "bad.csv"); }).find("bad.csv:2: R must hold 9 numbers"),
      std::string::npos);
  std::ofstream(dir / "cols.csv") << "1,2,3\n";
  EXPECT_NE(errorOf([&] { readBopResults(dir / "cols.csv"); }).find("expected 7"),
            std::string::npos);
  EXPECT_FALSE(errorOf([&] { writeBopResults(dir / "no" / "such" / "dir.csv", {r}); }).empty());
}

}  // namespace
}  // namespace stocs
