// `stocs overlay`: the estimated pose is drawn in colour, the truth outlined, bad inputs refused.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "stocs/io/bop_results.h"
#include "test_support.h"

namespace stocs {
namespace {

const std::string kTool = STOCS_TOOL_PATH;

TEST(CliOverlay, DrawsTheEstimateOverTheImageAndOutlinesTheTruth) {
  const std::filesystem::path root = test::scratchDir("overlay");
  const Eigen::Isometry3f truth = test::writeSyntheticBopDataset(root / "data");
  BopResult r;  // the truth itself, as an estimator would write it
  r.obj_id = 1;
  r.R = truth.linear().cast<double>();
  r.t_mm = truth.translation().cast<double>() * 1000.0;
  writeBopResults(root / "r.csv", {r});
  const std::string base = kTool + " overlay --dataset " + (root / "data").string() +
                           " --results " + (root / "r.csv").string();
  std::string out;
  ASSERT_EQ(test::runCommand(base + " --out " + (root / "o.png").string(), out), 0) << out;
  const cv::Mat image = cv::imread((root / "o.png").string(), cv::IMREAD_COLOR);
  ASSERT_EQ(image.cols, 320);
  ASSERT_EQ(image.rows, 240);
  // The object is at the image centre: tinted there (not grey), and white outline pixels exist.
  const cv::Vec3b centre = image.at<cv::Vec3b>(120, 160);
  EXPECT_FALSE(centre[0] == centre[1] && centre[1] == centre[2]);
  cv::Mat white;
  cv::inRange(image, cv::Scalar(250, 250, 250), cv::Scalar(255, 255, 255), white);
  EXPECT_GT(cv::countNonZero(white), 50);

  EXPECT_EQ(test::runCommand(base + " --image 7 --out " + (root / "x.png").string(), out), 2);
  EXPECT_NE(out.find("no image 7"), std::string::npos) << out;
  EXPECT_EQ(
      test::runCommand(kTool + " overlay --dataset " + (root / "data").string() + " --results " +
                           (root / "missing.csv").string() + " --out " + (root / "x.png").string(),
                       out),
      2);
  EXPECT_NE(out.find("missing.csv"), std::string::npos) << out;
}

}  // namespace
}  // namespace stocs
