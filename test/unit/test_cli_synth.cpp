// `stocs synth` and `stocs meshes` end to end: a generated scene that `stocs estimate` solves, and
// error exits.
#include <gtest/gtest.h>

#include "stocs/bop_dataset.h"
#include "stocs/bop_results.h"
#include "stocs/pose_metrics.h"
#include "stocs/surface_sampling.h"
#include "test_support.h"

namespace stocs {
namespace {

const std::string kTool = STOCS_TOOL_PATH;

TEST(CliSynth, EstimateFindsTheObjectsOfAGeneratedScene) {
  const auto root = test::scratchDir("synth_estimate");
  const std::string data = (root / "data").string();
  std::string out;
  ASSERT_EQ(test::runCommand(kTool + " synth --out " + data +
                                 " --objects 3 --distractors 1 --seed 4 --segmentation mild",
                             out),
            0)
      << out;
  EXPECT_NE(out.find("1 images in"), std::string::npos) << out;
  ASSERT_EQ(test::runCommand(kTool + " estimate --dataset " + data + " --out " +
                                 (root / "r.csv").string() + " --cache-dir " +
                                 (root / "cache").string() + " --bases 50",
                             out),
            0)
      << out;
  const BopDataset ds(data);
  const std::vector<BopGtInstance> truth = ds.sceneGroundTruth(0).at(0);
  const std::map<int, BopObjectInfo> info = ds.modelsInfo();
  int found = 0;
  std::string log;
  for (const BopResult& r : readBopResults(root / "r.csv")) {
    Rng rng(1);
    const MeshData mesh = loadMesh(ds.modelPath(r.obj_id).string(), 0.001f);
    std::vector<Eigen::Vector3f> points = sampleMeshSurface(mesh, 1000, rng).points;
    for (Eigen::Vector3f& p : points) p *= 1000;  // mm, like the results
    double adds = 1e9;
    for (const BopGtInstance& g : truth) {
      if (g.obj_id == r.obj_id)
        adds = std::min(adds, addsError(points, {r.R, r.t_mm}, {g.R, g.t_mm}));
    }
    found += adds < 0.1 * info.at(r.obj_id).diameter_mm;
    log += "object " + std::to_string(r.obj_id) + ": ADD-S " + std::to_string(adds) + " mm\n";
  }
  EXPECT_GE(found, 2) << log << out;
}

TEST(CliSynth, HelpListsTheProbabilitySourcesAndBadRequestsExitNonZero) {
  std::string out;
  ASSERT_EQ(test::runCommand(kTool + " estimate --help", out), 0);
  for (const char* expected :
       {"'real'", "'sim:PRESET'", "'simonly:PRESET'", "clean, mild, noisy, very-noisy"}) {
    EXPECT_NE(out.find(expected), std::string::npos) << expected << " missing from:\n" << out;
  }
  const auto root = test::scratchDir("synth_errors");
  ASSERT_EQ(test::runCommand(kTool + " synth --out " + (root / "d").string() + " --quiet", out), 0)
      << out;
  EXPECT_EQ(test::runCommand(kTool + " synth --out " + (root / "d").string(), out), 2);
  EXPECT_NE(out.find("exists and is not empty"), std::string::npos) << out;
  EXPECT_EQ(
      test::runCommand(kTool + " synth --out " + (root / "e").string() + " --segmentation x", out),
      2);
  EXPECT_NE(out.find("unknown segmentation preset 'x'"), std::string::npos) << out;
  EXPECT_NE(
      test::runCommand(kTool + " synth --out " + (root / "f").string() + " --distance 0.5", out),
      0);
  EXPECT_EQ(test::runCommand(kTool + " estimate --dataset " + (root / "d").string() +
                                 " --out x.csv --prob sim:grainy",
                             out),
            2);
  EXPECT_NE(out.find("unknown segmentation preset 'grainy'"), std::string::npos) << out;
}

TEST(CliSynth, MeshesWritesTheCatalogue) {
  const auto root = test::scratchDir("meshes");
  std::string out;
  ASSERT_EQ(test::runCommand(kTool + " meshes --out " + (root / "m").string(), out), 0) << out;
  EXPECT_NE(out.find("obj_000004.ply: mug"), std::string::npos) << out;
  EXPECT_TRUE(std::filesystem::exists(root / "m" / "models_info.json"));
}

}  // namespace
}  // namespace stocs
