// Depth, probability and boundary images of a BOP scene (decoding by OpenCV, then our validation):
// the input is written as each image file in turn and read by its BopDataset loader.
#include <opencv2/core.hpp>

#include "fuzz_support.h"
#include "stocs/io/bop_dataset.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using stocs::fuzz::parseInputAs;
  const std::filesystem::path root = stocs::fuzz::scratchDir() / "bop";
  std::filesystem::create_directories(root / "test" / "000001");
  std::filesystem::create_directories(root / "models");
  const stocs::BopDataset dataset(root);
  parseInputAs(dataset.depthPath(1, 0), data, size, [&] { dataset.loadDepth(1, 0); });
  parseInputAs(dataset.probabilityPath(1, 0, 1), data, size,
               [&] { dataset.loadProbability(1, 0, 1); });
  parseInputAs(dataset.boundaryPath(1, 0), data, size, [&] { dataset.loadBoundary(1, 0); });
  return 0;
}
