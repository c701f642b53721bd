// Mesh model files read through assimp (OBJ, STL, glTF, GLB) by stocs::loadMesh: any input must
// give a model or an InputError, never a crash, leak or undefined behaviour. The first byte picks
// the format (its extension), the rest is the file. assimp runs in a child process (its COLLADA
// parser's crash on fuzz/known_crashes/assimp_dae_null_read must become an InputError), so the
// fuzzer sees neither its coverage nor the sanitizers' reports from the child.
#include <iterator>

#include "fuzz_support.h"
#include "stocs/io/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const char* const kExtensions[] = {".obj", ".stl", ".dae", ".gltf", ".glb"};
  if (size == 0) return 0;
  const std::filesystem::path file =
      stocs::fuzz::scratchDir() /
      (std::string("model") + kExtensions[data[0] % std::size(kExtensions)]);
  stocs::fuzz::parseInputAs(file, data + 1, size - 1,
                            [&] { stocs::loadMesh(file.string(), 0.001f); });
  return 0;
}
