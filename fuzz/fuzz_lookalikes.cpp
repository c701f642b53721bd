// Look-alike files of generated datasets (models/lookalikes.json): the input is written as one and
// read by readLookalikes.
#include "fuzz_support.h"
#include "stocs/sim/lookalikes.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path file = stocs::fuzz::scratchDir() / "lookalikes.json";
  stocs::fuzz::parseInputAs(file, data, size, [&] { stocs::readLookalikes(file); });
  return 0;
}
