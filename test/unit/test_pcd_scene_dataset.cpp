// PCD registration scenes converted to BOP datasets: a generated scene with known intrinsics, and
// PCL's milk scene from the real-data folder.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "stocs/io/bop_dataset.h"
#include "stocs/io/mesh_io.h"
#include "stocs/io/pcd_scene_dataset.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

/// Writes an ascii PCD; organized (width x height) when `height` > 1, with colour when `rgb`.
void writePcd(const std::filesystem::path& file, const std::vector<Eigen::Vector3f>& points,
              int width, int height, bool rgb) {
  std::ofstream out(file);
  out << "VERSION .7\nFIELDS x y z" << (rgb ? " rgba" : "") << "\nSIZE 4 4 4" << (rgb ? " 4" : "")
      << "\nTYPE F F F" << (rgb ? " U" : "") << "\nCOUNT 1 1 1" << (rgb ? " 1" : "") << "\nWIDTH "
      << width << "\nHEIGHT " << height << "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << points.size()
      << "\nDATA ascii\n";
  out.precision(9);
  for (const Eigen::Vector3f& p : points) {
    out << p.x() << ' ' << p.y() << ' ' << p.z() << (rgb ? " 4286611584" : "") << '\n';
  }
}

class PcdSceneTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratchDir("pcd_scene");
    k_.fx = k_.fy = 300;
    k_.cx = 160;
    k_.cy = 120;
    k_.width = 320;
    k_.height = 240;
    // A box in front of a wall; the model is the box's visible points, cut out of the scene.
    const Eigen::Isometry3f box_pose = test::viewingPose(0.6f);
    Eigen::Isometry3f wall_pose = Eigen::Isometry3f::Identity();
    wall_pose.translation() = Eigen::Vector3f(0, 0, 1.0f);
    cv::Mat labels;
    const cv::Mat depth = test::renderDepth(
        {{boxMesh({0.1f, 0.06f, 0.04f}), box_pose}, {boxMesh({2, 2, 0.01f}), wall_pose}}, k_,
        &labels);
    std::vector<Eigen::Vector3f> scene, model;
    for (int v = 0; v < k_.height; ++v) {
      for (int u = 0; u < k_.width; ++u) {
        const float z = depth.at<float>(v, u);
        const Eigen::Vector3f p =
            z > 0 ? Eigen::Vector3f((u - k_.cx) * z / k_.fx, (v - k_.cy) * z / k_.fy, z)
                  : Eigen::Vector3f::Constant(NAN);
        scene.push_back(p);
        if (labels.at<int>(v, u) == 1) model.push_back(p);
      }
    }
    model_points_ = static_cast<int>(model.size());
    for (const Eigen::Vector3f& p : model) model_box_.extend(p.cast<double>());
    writePcd(dir_ / "scene.pcd", scene, k_.width, k_.height, true);
    writePcd(dir_ / "model.pcd", model, static_cast<int>(model.size()), 1, false);
    std::ofstream(dir_ / "gt.json")
        << R"({"model": "model.pcd", "scene": "scene.pcd", "units": "m", "T_scene_from_model": )"
        << "[[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}";
  }

  std::filesystem::path dir_;
  CameraIntrinsics k_;
  int model_points_ = 0;
  Eigen::AlignedBox3d model_box_;
};

TEST_F(PcdSceneTest, ConvertsToAOneImageBopDataset) {
  ASSERT_TRUE(isPcdSceneFolder(dir_));
  const std::filesystem::path out = dir_ / "bop";
  EXPECT_EQ(convertPcdSceneToBop(dir_, out), model_points_);
  EXPECT_FALSE(isPcdSceneFolder(out));

  const BopDataset ds(out);
  const BopFrameCamera cam = ds.sceneCameras(0).at(0);
  EXPECT_NEAR(cam.K(0, 0), k_.fx, 1e-2);
  EXPECT_NEAR(cam.K(1, 1), k_.fy, 1e-2);
  EXPECT_NEAR(cam.K(0, 2), k_.cx, 1e-2);
  EXPECT_NEAR(cam.K(1, 2), k_.cy, 1e-2);
  EXPECT_DOUBLE_EQ(cam.depth_scale, 0.1);
  // The model is recentred on its bounding box; the ground truth moves it back.
  const BopGtInstance gt = ds.sceneGroundTruth(0).at(0).at(0);
  EXPECT_EQ(gt.obj_id, 1);
  EXPECT_TRUE(gt.R.isIdentity());
  EXPECT_LT((gt.t_mm - model_box_.center() * 1000).norm(), 1e-3);
  Eigen::AlignedBox3d written;
  for (const Eigen::Vector3f& v : loadMesh(ds.modelPath(1).string(), 0.001f).vertices) {
    written.extend(v.cast<double>());
  }
  EXPECT_LT(written.center().norm(), 1e-6);
  EXPECT_NEAR(written.sizes().norm(), model_box_.sizes().norm(), 1e-6);
  EXPECT_GT(ds.modelsInfo().at(1).diameter_mm, 50);

  const cv::Mat depth = ds.loadDepth(0, 0);
  EXPECT_NEAR(depth.at<uint16_t>(k_.height - 1, 0) * 0.1, 1000 - 5, 0.1);  // the wall, in mm
  const cv::Mat mask = cv::imread(ds.maskVisibPath(0, 0, 0).string(), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(cv::countNonZero(mask), model_points_);
}

TEST_F(PcdSceneTest, BadFilesAreNamed) {
  std::ofstream(dir_ / "gt.json")
      << R"({"model": "model.pcd", "scene": "scene.pcd", "units": "in",)"
      << R"( "T_scene_from_model": [[1]]})";
  try {
    convertPcdSceneToBop(dir_, dir_ / "bop");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("gt.json: units must be"), std::string::npos) << e.what();
  }
  std::ofstream(dir_ / "gt.json") << R"({"model": "model.pcd", "scene": "nope.pcd", )"
                                  << R"("T_scene_from_model": [[1, 0, 0, 0], [0, 1, 0, 0], )"
                                  << R"([0, 0, 1, 0], [0, 0, 0, 1]]})";
  EXPECT_THROW(convertPcdSceneToBop(dir_, dir_ / "bop"), InputError);
}

TEST(PcdSceneReal, PclMilk) {
  STOCS_REQUIRE_DATASETS(root);
  const std::filesystem::path out = test::scratchDir("milk");
  ASSERT_TRUE(isPcdSceneFolder(root / "pcl-milk"));
  // Every model point is a scene point (gt.json's check).
  EXPECT_EQ(convertPcdSceneToBop(root / "pcl-milk", out), 13704);
  const BopFrameCamera cam = BopDataset(out).sceneCameras(0).at(0);
  EXPECT_NEAR(cam.K(0, 0), 525, 1);  // the Kinect's usual focal length
  EXPECT_NEAR(cam.K(0, 2), 319.5, 1);
}

}  // namespace
}  // namespace stocs
