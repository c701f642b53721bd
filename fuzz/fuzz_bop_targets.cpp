// BOP targets files (test_targets_bop19.json): the input is written as one and read by
// readBopTargets.
#include "fuzz_support.h"
#include "stocs/io/bop_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path file = stocs::fuzz::scratchDir() / "test_targets_bop19.json";
  stocs::fuzz::parseInputAs(file, data, size, [&] { stocs::readBopTargets(file); });
  return 0;
}
