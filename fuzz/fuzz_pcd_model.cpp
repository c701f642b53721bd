// PCD model files (ascii, binary and binary_compressed) through stocs::loadMesh: any input must
// give a model or an InputError, never a crash, leak or undefined behaviour.
#include "fuzz_support.h"
#include "stocs/io/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path file = stocs::fuzz::scratchDir() / "model.pcd";
  stocs::fuzz::parseInputAs(file, data, size, [&] { stocs::loadMesh(file.string(), 1.0f); });
  return 0;
}
