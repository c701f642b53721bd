// `stocs synth`, `stocs simstats` and `stocs meshes` end to end: a generated scene that
// `stocs estimate` solves, presets ranked by simstats, and error exits.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "stocs/eval/pose_metrics.h"
#include "stocs/geometry/surface_sampling.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/io/bop_results.h"
#include "stocs/io/mesh_io.h"
#include "test_support.h"

namespace stocs {
namespace {

const std::string kTool = STOCS_TOOL_PATH;

/// Runs `stocs estimate` with probability source `prob` (default if empty) on image 0 of scene 0
/// and returns the objects of the ground truth whose estimate is within 10% of the diameter
/// (ADD-S against the nearest instance); `log` gets each object's error and the tool's output.
std::set<int> objectsFound(const std::filesystem::path& data, const std::filesystem::path& work,
                           const std::string& prob, std::string& log) {
  std::string file = "r" + prob + ".csv";
  std::replace(file.begin(), file.end(), '/', '_');  // onnx:models/...
  const std::filesystem::path results = work / file;
  std::string out;
  const std::string source = prob.empty() ? "" : " --prob " + prob;
  EXPECT_EQ(test::runCommand(kTool + " estimate --dataset " + data.string() + " --out " +
                                 results.string() + " --cache-dir " + (work / "cache").string() +
                                 " --bases 50" + source,
                             out),
            0);
  log += out;
  const BopDataset ds(data);
  const std::vector<BopGtInstance> truth = ds.sceneGroundTruth(0).at(0);
  const std::map<int, BopObjectInfo> info = ds.modelsInfo();
  std::set<int> found;
  for (const BopResult& r : readBopResults(results)) {
    Rng rng(1);
    const MeshData mesh = loadMesh(ds.modelPath(r.obj_id).string(), 0.001f);
    std::vector<Eigen::Vector3f> points = sampleMeshSurface(mesh, 1000, rng).points;
    for (Eigen::Vector3f& p : points) p *= 1000;  // mm, like the results
    double adds = 1e9;
    for (const BopGtInstance& g : truth) {
      if (g.obj_id == r.obj_id)
        adds = std::min(adds, addsError(points, {r.R, r.t_mm}, {g.R, g.t_mm}));
    }
    if (adds < 0.1 * info.at(r.obj_id).diameter_mm) found.insert(r.obj_id);
    log += fmt::format("{}object {}: ADD-S {:.1f} mm\n", prob, r.obj_id, adds);
  }
  return found;
}

TEST(CliSynth, EstimateFindsEveryObjectOfAGeneratedScene) {
  const auto root = test::scratchDir("synth_estimate");
  const std::filesystem::path data = root / "data";
  std::string out;
  ASSERT_EQ(test::runCommand(kTool + " synth --out " + data.string() +
                                 " --objects 3 --distractors 2 --seed 4 --segmentation mild",
                             out),
            0)
      << out;
  EXPECT_NE(out.find("1 images in"), std::string::npos) << out;
  std::set<int> truth;
  const std::map<int, std::vector<BopGtInstance>> gt = BopDataset(data).sceneGroundTruth(0);
  for (const BopGtInstance& g : gt.at(0)) truth.insert(g.obj_id);
  ASSERT_EQ(truth.size(), 3u);
  // The prob/ maps that synth wrote, maps simulated on the fly from the masks by a noisier
  // preset, and the package's own network on rgb/ (trained on other seeds' scenes).
  for (const std::string prob : {"", "simonly:noisy", "onnx:models/segmenter.onnx"}) {
    std::string log;
    EXPECT_EQ(objectsFound(data, root, prob, log), truth) << log;
  }
}

TEST(CliSynth, HelpListsTheProbabilitySourcesAndBadRequestsExitNonZero) {
  std::string out;
  ASSERT_EQ(test::runCommand(kTool + " estimate --help", out), 0);
  for (const char* expected : {"'real'", "'sim:PRESET'", "'simonly:PRESET'", "'onnx:MODEL'",
                               "clean, mild, noisy, very-noisy"}) {
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
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {" --scenes 0", "--scenes 0 is outside [1, 100000]"},
           {" --objects 0", "--objects 0 is outside [1, 100]"},
           {" --absent -1", "--absent -1 is outside [0, 100]"},
           {" --width 0", "camera intrinsics are invalid (width 0"},
           {" --depth-noise -1", "--depth-noise -1 is outside [0, 10]"},
           {" --min-distance 0.9 --max-distance 0.5", "max_distance 0.5 m is below min_distance"},
           {" --max-elevation 90", "--max-elevation 90 deg is outside [5, 85]"},
           {" --light-direction 90", "--light-direction 90 deg is outside [0, 80]"},
           {" --light-colour -0.1", "--light-colour -0.1 is outside [0, 0.5]"},
           {" --lookalike-share 1.5", "--lookalike-share 1.5 is outside [0, 1]"},
           {" --models " + (root / "none").string(), "not a folder"},
           {" --catalogue plain",
            "catalogue 'plain': unknown (use standard, textured, all, lookalike)"},
           {" --packed-bin 99", "--packed-bin 99: no such object among the models (1, 2, 3"},
           {" --packed-bin 1 --bin-rows 0", "--bin-rows 0 is outside [1, 20]"},
           {" --packed-bin 1 --sequence",
            "--packed-bin 1 makes random views of a bin; it does "
            "not apply to a sequence"},
           {" --catalogue textured --models " + (root / "none").string(),
            "--catalogue textured selects generated objects: it does not apply with --models"},
           {" --sequence --rotation-speed -1", "--rotation-speed -1 rad/s is outside [0, 20]"},
           {" --sequence --rate 0", "--rate 0 Hz is outside (0, 1000]"},
           {" --sequence --frames 100",
            "the lift (--lift-start 90, --lift-frames 60) ends at frame 149, after the "
            "sequence's last frame 99 (--frames 100)"},
           {" --sequence --images 2", "--images 2 does not apply to a sequence"}}) {
    EXPECT_EQ(test::runCommand(kTool + " synth --out " + (root / "g").string() + args, out), 2)
        << args;
    EXPECT_NE(out.find(message), std::string::npos) << args << ": " << out;
  }
  EXPECT_FALSE(std::filesystem::exists(root / "g" / "test" / "000000")) << "written anyway";
  EXPECT_EQ(test::runCommand(kTool + " estimate --dataset " + (root / "d").string() +
                                 " --out x.csv --prob sim:grainy",
                             out),
            2);
  EXPECT_NE(out.find("unknown segmentation preset 'grainy'"), std::string::npos) << out;
  EXPECT_EQ(test::runCommand(kTool + " simmaps --dataset " + (root / "none").string() + " --out " +
                                 (root / "h").string(),
                             out),
            2);
  EXPECT_NE(out.find("not a folder"), std::string::npos) << out;
}

/// The numbers in the columns of the simstats row for `source` after its name (maps, precision,
/// recall and, with --recall-floor, the maps at or below it); empty when there is no such row.
std::vector<double> simstatsColumns(const std::string& table, const std::string& source) {
  const size_t row = table.find("| " + source + " |");
  if (row == std::string::npos) return {};
  const size_t start = row + source.size() + 4;
  std::stringstream line(table.substr(start, table.find('\n', row) - start));
  std::vector<double> columns;
  for (std::string cell; std::getline(line, cell, '|');) {
    if (cell.find_first_of("0123456789") != std::string::npos) columns.push_back(std::stod(cell));
  }
  return columns;
}

/// The recall column of the simstats row for `source`, percent; -1 when there is no such row.
double simstatsRecall(const std::string& table, const std::string& source) {
  const std::vector<double> columns = simstatsColumns(table, source);
  return columns.size() >= 3 ? columns[2] : -1;
}

TEST(CliSynth, SimstatsRanksThePresetsOnAGeneratedDataset) {
  const auto root = test::scratchDir("simstats");
  const std::string data = (root / "d").string();
  std::string out;
  ASSERT_EQ(test::runCommand(kTool + " synth --out " + data + " --objects 3 --quiet", out), 0)
      << out;
  ASSERT_EQ(test::runCommand(kTool + " simstats --dataset " + data + " --seeds 2", out), 0) << out;
  // synth's prob/ maps are the mild preset with other seeds.
  std::vector<double> recall;
  for (const char* source :
       {"simulator, clean", "dataset's prob/ maps", "simulator, noisy", "simulator, very-noisy"}) {
    recall.push_back(simstatsRecall(out, source));
    ASSERT_GE(recall.back(), 0) << source << " missing from:\n" << out;
  }
  EXPECT_GT(recall[0], 98) << out;
  for (size_t k = 1; k < recall.size(); ++k) EXPECT_LT(recall[k], recall[k - 1]) << out;
  EXPECT_NE(out.find("| d | mask_visib |"), std::string::npos) << out;

  EXPECT_EQ(
      test::runCommand(kTool + " simstats --dataset " + data + " --presets clean,grainy", out), 2);
  EXPECT_NE(out.find("unknown segmentation preset 'grainy'"), std::string::npos) << out;
  EXPECT_EQ(test::runCommand(kTool + " simstats --dataset " + (root / "none").string(), out), 2);
  EXPECT_NE(out.find("not a folder"), std::string::npos) << out;
}

TEST(CliSynth, SimstatsCountsTheMapsAtOrBelowARecallFloor) {
  const auto root = test::scratchDir("simstats_floor");
  const std::string data = (root / "d").string();
  std::string out;
  ASSERT_EQ(
      test::runCommand(kTool + " synth --out " + data + " --objects 3 --images 4 --quiet", out), 0)
      << out;
  const std::string simstats =
      kTool + " simstats --dataset " + data + " --presets clean,very-noisy --seeds 1";
  ASSERT_EQ(test::runCommand(simstats + " --recall-floor 1", out), 0) << out;
  EXPECT_NE(out.find("| maps with recall <= 1 |"), std::string::npos) << out;
  for (const char* source : {"simulator, clean", "simulator, very-noisy"}) {
    const std::vector<double> columns = simstatsColumns(out, source);
    ASSERT_EQ(columns.size(), 4u) << source << " in:\n" << out;
    EXPECT_EQ(columns[3], columns[0]) << "every map's recall is at most 1:\n" << out;
  }
  ASSERT_EQ(test::runCommand(simstats + " --recall-floor 0.9", out), 0) << out;
  const std::vector<double> clean = simstatsColumns(out, "simulator, clean");
  const std::vector<double> noisy = simstatsColumns(out, "simulator, very-noisy");
  ASSERT_EQ(clean.size(), 4u) << out;
  ASSERT_EQ(noisy.size(), 4u) << out;
  EXPECT_LT(clean[3], noisy[3]) << out;
  EXPECT_EQ(simstatsColumns(out, "dataset's prob/ maps").size(), 4u) << out;

  EXPECT_NE(test::runCommand(simstats + " --recall-floor 1.5", out), 0);
  EXPECT_NE(out.find("--recall-floor"), std::string::npos) << out;
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
