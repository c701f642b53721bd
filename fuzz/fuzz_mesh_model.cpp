// Mesh model files read through assimp (OBJ, STL, glTF, GLB) by stocs::loadMesh: any input must
// give a model or an InputError, never a crash, leak or undefined behaviour. The first byte picks
// the format (its extension), the rest is the file. DAE is left out: Debian's assimp 5.2.5 reads
// through a null pointer in its COLLADA parser on malformed files (fuzz/known_crashes), which no
// check before it can rule out.
#include <iterator>

#include "fuzz_support.h"
#include "stocs/io/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const char* const kExtensions[] = {".obj", ".stl", ".dae", ".gltf", ".glb"};
  if (size == 0) return 0;
  if (data[0] % std::size(kExtensions) == 2) return 0;  // DAE: see above
  const std::filesystem::path file =
      stocs::fuzz::scratchDir() /
      (std::string("model") + kExtensions[data[0] % std::size(kExtensions)]);
  stocs::fuzz::parseInputAs(file, data + 1, size - 1,
                            [&] { stocs::loadMesh(file.string(), 0.001f); });
  return 0;
}
