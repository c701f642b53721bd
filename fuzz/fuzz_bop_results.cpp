// BOP result files (CSV, read by the evaluation tools) through stocs::readBopResults.
#include "fuzz_support.h"
#include "stocs/io/bop_results.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path file = stocs::fuzz::scratchDir() / "results.csv";
  stocs::fuzz::parseInputAs(file, data, size, [&] { stocs::readBopResults(file); });
  return 0;
}
