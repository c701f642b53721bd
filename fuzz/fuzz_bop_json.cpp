// The BOP JSON files (scene_camera.json, scene_gt.json, models/models_info.json): the input is
// written as each of them in turn and read by its BopDataset parser.
#include "fuzz_support.h"
#include "stocs/io/bop_dataset.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using stocs::fuzz::parseInputAs;
  const std::filesystem::path root = stocs::fuzz::scratchDir() / "bop";
  const std::filesystem::path scene = root / "test" / "000001";
  std::filesystem::create_directories(scene);
  std::filesystem::create_directories(root / "models");
  const stocs::BopDataset dataset(root);
  parseInputAs(scene / "scene_camera.json", data, size, [&] { dataset.sceneCameras(1); });
  parseInputAs(scene / "scene_gt.json", data, size, [&] { dataset.sceneGroundTruth(1); });
  parseInputAs(root / "models" / "models_info.json", data, size, [&] { dataset.modelsInfo(); });
  return 0;
}
