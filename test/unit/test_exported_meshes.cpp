// The LM-O cat exported by scripts/export_test_meshes.py to OBJ, binary STL (origin moved by a
// known offset), DAE (Z_UP, two nodes) and GLB, all in metres, gives on the real frame the pose the
// BOP PLY in mm gives, up to that offset (issue 31).
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <opencv2/core.hpp>

#include "stocs/estimation/pipeline.h"
#include "stocs/eval/pose_metrics.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/io/mesh_io.h"
#include "test_support.h"

namespace stocs {
namespace {

namespace fs = std::filesystem;

constexpr int kScene = 2, kImage = 3, kCat = 6;
const Eigen::Vector3f kStlOffset(0.04f, -0.03f, 0.05f);  // metres added to the STL's vertices

struct CatFrame {
  OrganizedCloud cloud;
  float focal_px;
  cv::Mat probability, boundary;
};

CatFrame loadCatFrame(const BopDataset& ds) {
  const cv::Mat depth = ds.loadDepth(kScene, kImage);
  const BopFrameCamera cam = ds.sceneCameras(kScene).at(kImage);
  const CameraIntrinsics k = cam.intrinsics(depth.cols, depth.rows);
  return {cloudFromDepth(depth, k, cam.depth_scale / 1000), static_cast<float>(k.fx),
          ds.loadProbability(kScene, kImage, kCat), ds.loadBoundary(kScene, kImage)};
}

Eigen::Isometry3f estimateCat(const CatFrame& frame, const ModelCache& cache, const fs::path& model,
                              float unit_scale) {
  PipelineParams params;
  params.stocs.seed = 1;
  const PreparedModel prepared = cache.load(model.string(), unit_scale, params.model);
  const PoseEstimate r = detectObject(frame.cloud, frame.focal_px, frame.probability, prepared,
                                      params, frame.boundary.empty() ? nullptr : &frame.boundary);
  EXPECT_TRUE(r.found()) << model;
  return r.found() ? r.best().pose : Eigen::Isometry3f::Identity();
}

/// Mean distance (mm) between the PLY's vertices placed by `ply_pose` and the same vertices,
/// moved by `offset` as in the exported file, placed by `pose`.
double addMm(const MeshData& ply, const Eigen::Isometry3f& ply_pose, const Eigen::Isometry3f& pose,
             const Eigen::Vector3f& offset) {
  double sum = 0;
  for (const Eigen::Vector3f& v : ply.vertices) {
    sum += (ply_pose * v - pose * (v + offset)).norm();
  }
  return 1000 * sum / static_cast<double>(ply.vertices.size());
}

TEST(ExportedMeshes, LmoCatGivesThePlysPoseInEveryFormat) {
  STOCS_REQUIRE_DATASETS(root);
  const BopDataset ds(root / "lmo-cat");
  const fs::path ply = ds.modelPath(kCat);
  const fs::path out = test::scratchDir("exported_meshes");
  std::string log;
  ASSERT_EQ(test::runCommand(fmt::format("/usr/bin/python3 scripts/export_test_meshes.py --out {} "
                                         "--offset {} {} {} {}",
                                         out.string(), kStlOffset.x(), kStlOffset.y(),
                                         kStlOffset.z(), ply.string()),
                             log),
            0)
      << log;
  const CatFrame frame = loadCatFrame(ds);
  const ModelCache cache(out / "cache");
  const Eigen::Isometry3f ply_pose = estimateCat(frame, cache, ply, 0.001f);
  const MeshData ply_mesh = loadMesh(ply.string(), 0.001f);

  const std::vector<BopGtInstance> instances = ds.sceneGroundTruth(kScene).at(kImage);
  const BopGtInstance truth = *std::find_if(
      instances.begin(), instances.end(), [](const BopGtInstance& g) { return g.obj_id == kCat; });
  std::vector<Eigen::Vector3f> mm;
  for (const Eigen::Vector3f& v : ply_mesh.vertices) mm.push_back(v * 1000.0f);
  const RigidPose estimate{ply_pose.linear().cast<double>(),
                           ply_pose.translation().cast<double>() * 1000};
  ASSERT_LT(addsError(mm, estimate, {truth.R, truth.t_mm}),
            0.1 * ds.modelsInfo().at(kCat).diameter_mm)
      << "the PLY's own pose is wrong: nothing to compare with";

  const std::pair<const char*, Eigen::Vector3f> files[] = {{"obj_000006.obj", {0, 0, 0}},
                                                           {"obj_000006.stl", kStlOffset},
                                                           {"obj_000006.dae", {0, 0, 0}},
                                                           {"obj_000006.glb", {0, 0, 0}}};
  for (const auto& [name, offset] : files) {
    const Eigen::Isometry3f pose = estimateCat(frame, cache, out / name, 1.0f);
    EXPECT_LT(addMm(ply_mesh, ply_pose, pose, offset), 1.0) << name;
  }
}

}  // namespace
}  // namespace stocs
