// Mesh model files read through assimp (OBJ, STL, DAE, glTF, GLB): any input must give a model or
// an InputError, never a crash, leak or undefined behaviour. The first byte picks the format (its
// extension), the rest is the file. OBJ, STL, glTF and GLB go to the assimp reader in this process,
// so the fuzzer sees the coverage and the sanitizers' reports of assimp and of the merge; DAE goes
// through stocs::loadMesh, which reads it in the program stocs_mesh_reader: Debian's assimp 5.2.5
// crashes in its COLLADA parser on some malformed files (fuzz/known_crashes), which must become an
// InputError.
#include <iterator>

#include "assimp_model.h"
#include "fuzz_support.h"
#include "stocs/io/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const char* const kExtensions[] = {".obj", ".stl", ".dae", ".gltf", ".glb"};
  if (size == 0) return 0;
  const std::filesystem::path file =
      stocs::fuzz::scratchDir() /
      (std::string("model") + kExtensions[data[0] % std::size(kExtensions)]);
  const std::string ext = file.extension().string();
  stocs::fuzz::parseInputAs(file, data + 1, size - 1, [&] {
    if (ext == ".dae") {
      stocs::loadMesh(file.string(), 0.001f);
    } else {
      stocs::detail::readAssimpModel(file.string(), ext);
    }
  });
  return 0;
}
