// Acceptance on real data: the two frames of ../shared/datasets with real network probability maps
// (LM-O cat; Rutgers packed bin scene 0, dove). With default parameters the pose must be within
// ADD-S < 10% of the diameter of a ground-truth instance, and accepted by its confidence, for at
// least 9 of 10 seeds.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "stocs/estimation/pipeline.h"
#include "stocs/eval/pose_metrics.h"
#include "stocs/io/bop_dataset.h"
#include "test_support.h"

namespace stocs {
namespace {

struct Frame {
  const char* dataset;
  int scene, image, object;
};

void expectNineOfTenSeeds(const std::filesystem::path& root, const Frame& f) {
  const BopDataset ds(root / f.dataset);
  const PipelineParams params;
  const ModelCache cache(test::scratchDir(std::string("real_cache_") + f.dataset));
  const PreparedModel model = cache.load(ds.modelPath(f.object).string(), 0.001f, params.model);
  const cv::Mat depth = ds.loadDepth(f.scene, f.image);
  const BopFrameCamera cam = ds.sceneCameras(f.scene).at(f.image);
  const CameraIntrinsics k = cam.intrinsics(depth.cols, depth.rows);
  const OrganizedCloud cloud = cloudFromDepth(depth, k, cam.depth_scale / 1000);
  const cv::Mat probability = ds.loadProbability(f.scene, f.image, f.object);
  const cv::Mat boundary = ds.loadBoundary(f.scene, f.image);
  const double diameter = ds.modelsInfo().at(f.object).diameter_mm;
  const std::vector<BopGtInstance> truth = ds.sceneGroundTruth(f.scene).at(f.image);

  std::vector<Eigen::Vector3f> points_mm;
  for (const Eigen::Vector3f& p : model.model.points) points_mm.push_back(p * 1000.0f);
  int successes = 0;
  std::string log;
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    PipelineParams p = params;
    p.stocs.seed = seed;
    const PoseEstimate r = detectObject(cloud, static_cast<float>(k.fx), probability, model, p,
                                        boundary.empty() ? nullptr : &boundary);
    double best = 1e9;
    if (r.found() && r.instances.front().accepted) {  // a rejected pose is not published
      const RigidPose est{r.best().pose.linear().cast<double>(),
                          r.best().pose.translation().cast<double>() * 1000};
      for (const BopGtInstance& g : truth) {
        if (g.obj_id == f.object) best = std::min(best, addsError(points_mm, est, {g.R, g.t_mm}));
      }
    }
    successes += best < 0.1 * diameter;
    log += "seed " + std::to_string(seed) + ": ADD-S " + std::to_string(best) + " mm" +
           (r.found() ? ", confidence " + std::to_string(r.instances.front().confidence) : "") +
           "\n";
  }
  EXPECT_GE(successes, 9) << f.dataset << " (diameter " << diameter << " mm)\n" << log;
}

TEST(RealFrames, LinemodOccludedCat) {
  STOCS_REQUIRE_DATASETS(root);
  expectNineOfTenSeeds(root, {"lmo-cat", 2, 3, 6});
}

TEST(RealFrames, PackedBinDove) {
  STOCS_REQUIRE_DATASETS(root);
  expectNineOfTenSeeds(root, {"rutgers-packed", 0, 0, 1});
}

}  // namespace
}  // namespace stocs
