// The `stocs` tool on bad files (rows of docs/bad_inputs.md): bad models and unit
// mistakes exit 2 with the message naming the file; a corrupt or unwritable cache never stops a
// run; an out-of-range probability map in a dataset exits 2 naming the file and pixel; bad
// segmentation inputs (--prob masks, boxes:FILE) exit 2 naming the file.
#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "stocs/io/ply_writer.h"
#include "stocs/sim/shape_meshes.h"
#include "test_support.h"

namespace stocs {
namespace {

const std::string kTool = STOCS_TOOL_PATH;

/// Runs `stocs ARGS`; returns the exit code and puts stdout + stderr in `out`.
int stocs(const std::string& args, std::string& out) {
  return test::runCommand(kTool + " " + args, out);
}

TEST(CliBadInput, BadModelFilesExitTwoNamingTheFile) {
  const auto dir = test::scratchDir("cli_bad_models");
  std::string out;
  std::ofstream(dir / "empty.ply").flush();
  EXPECT_EQ(stocs("prepare --no-cache " + (dir / "empty.ply").string(), out), 2);
  EXPECT_NE(out.find("stocs: error: model " + (dir / "empty.ply").string() + ": file is empty"),
            std::string::npos)
      << out;
  std::ofstream(dir / "garbage.ply") << "this is not a ply file\n";
  EXPECT_EQ(stocs("prepare --no-cache " + (dir / "garbage.ply").string(), out), 2);
  EXPECT_NE(out.find("model " + (dir / "garbage.ply").string() + ": not a PLY file"),
            std::string::npos)
      << out;
}

TEST(CliBadInput, AMillimetreModelDeclaredAsMetresIsRefused) {
  const auto dir = test::scratchDir("cli_unit_mistake");
  writePly(dir / "box.ply", boxMesh({100, 60, 40}));  // millimetres
  std::string out;
  EXPECT_EQ(stocs("prepare --no-cache --model-scale 1 " + (dir / "box.ply").string(), out), 2);
  EXPECT_NE(out.find("is implausible for an object; is the unit scale right? (BOP models are in "
                     "mm: use 0.001)"),
            std::string::npos)
      << out;
  EXPECT_EQ(stocs("prepare --no-cache --model-scale 0.001 " + (dir / "box.ply").string(), out), 0)
      << out;
}

TEST(CliBadInput, MeshFormatModelsArePreparedOrRefusedNamingTheFile) {
  const auto dir = test::scratchDir("cli_mesh_formats");
  std::ofstream(dir / "quad.obj") << "mtllib gone.mtl\nv 0 0 0\nv 100 0 0\nv 100 50 0\nv 0 50 20\n"
                                     "f 1 2 3 4\n";
  std::string out;
  EXPECT_EQ(stocs("prepare --no-cache " + (dir / "quad.obj").string(), out), 0) << out;
  EXPECT_EQ(stocs("prepare --no-cache --model-scale 1 " + (dir / "quad.obj").string(), out), 2);
  EXPECT_NE(out.find("if the file is in mm use unit scale 0.001"), std::string::npos) << out;
  std::ofstream(dir / "bad.stl") << "solid x\nfacet normal a b c\n";
  EXPECT_EQ(stocs("prepare --no-cache " + (dir / "bad.stl").string(), out), 2);
  EXPECT_NE(
      out.find("stocs: error: model " + (dir / "bad.stl").string() + ": not a readable STL file"),
      std::string::npos)
      << out;
}

TEST(CliBadInput, ACorruptOrUnwritableCacheIsRebuiltOrSkipped) {
  const auto dir = test::scratchDir("cli_bad_cache");
  writePly(dir / "box.ply", boxMesh({100, 60, 40}));
  const std::string model = (dir / "box.ply").string();
  std::string out;
  ASSERT_EQ(stocs("prepare --cache-dir " + (dir / "cache").string() + " " + model, out), 0) << out;
  EXPECT_NE(out.find("built and cached"), std::string::npos) << out;
  for (const auto& entry : std::filesystem::directory_iterator(dir / "cache")) {
    std::filesystem::resize_file(entry.path(), std::filesystem::file_size(entry.path()) / 2);
  }
  ASSERT_EQ(stocs("prepare --cache-dir " + (dir / "cache").string() + " " + model, out), 0) << out;
  EXPECT_NE(out.find("rebuilt (invalid cache entry)"), std::string::npos) << out;
  EXPECT_NE(out.find("note: cache entry"), std::string::npos) << out;
  EXPECT_NE(out.find("truncated"), std::string::npos) << out;

  std::ofstream(dir / "blocker") << "a file where the cache folder should be";
  ASSERT_EQ(stocs("prepare --cache-dir " + (dir / "blocker" / "cache").string() + " " + model, out),
            0)
      << out;
  EXPECT_NE(out.find("built (not cached)"), std::string::npos) << out;
}

TEST(CliBadInput, AnOutOfRangeProbabilityMapExitsTwoNamingThePixel) {
  const auto root = test::scratchDir("cli_bad_probability");
  test::writeSyntheticBopDataset(root / "data");
  const auto prob = root / "data" / "test" / "000000" / "prob" / "000000_000001.png";
  cv::Mat map = cv::imread(prob.string(), cv::IMREAD_UNCHANGED);
  map.at<uint16_t>(3, 5) = 20000;  // 2.0 at scale 1/10000
  cv::imwrite(prob.string(), map);
  std::string out;
  EXPECT_EQ(stocs("estimate --no-cache --dataset " + (root / "data").string() + " --out " +
                      (root / "x.csv").string(),
                  out),
            2);
  EXPECT_NE(out.find(prob.string() + ": probability image value 2 at pixel (u=5, v=3) is outside "
                                     "[0, 1] (raw value / 10000)"),
            std::string::npos)
      << out;
}

TEST(CliBadInput, BadSegmentationInputsExitTwoNamingTheFile) {
  const auto root = test::scratchDir("cli_bad_segmentation");
  test::writeSyntheticBopDataset(root / "data");
  const std::string run = "estimate --no-cache --dataset " + (root / "data").string() + " --out " +
                          (root / "x.csv").string() + " --prob ";
  std::string out;
  // Without mask_visib/ the masks are rendered from the model: the box is found.
  EXPECT_EQ(stocs(run + "masks", out), 0) << out;
  EXPECT_NE(out.find("1 of 1 objects found"), std::string::npos) << out;
  const auto boxes = root / "boxes.json";
  for (const auto& [text, problem] : std::vector<std::pair<std::string, std::string>>{
           {"[{\"scene_id\": 0}", "invalid JSON"},
           {R"([{"scene_id": 0, "image_id": 0, "category_id": 7, "bbox": [1, 1, 5, 5],
                "score": 1}])",
            "scene 0 image 0 has a box of category_id 7, which is not an object of the dataset"}}) {
    std::ofstream(boxes) << text;
    EXPECT_EQ(stocs(run + "boxes:" + boxes.string(), out), 2) << out;
    EXPECT_NE(out.find(boxes.string() + ": " + problem), std::string::npos) << out;
  }
  // A mask_visib/ folder without the instance's mask is an error, not a reason to render.
  std::filesystem::create_directories(root / "data" / "test" / "000000" / "mask_visib");
  EXPECT_EQ(stocs(run + "masks", out), 2) << out;
  EXPECT_NE(out.find("mask_visib/000000_000000.png: no such file"), std::string::npos) << out;
}

}  // namespace
}  // namespace stocs
