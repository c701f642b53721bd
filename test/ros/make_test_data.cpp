// Writes the generated data the ROS integration tests play: the one-image BOP dataset of the CLI
// test (an asymmetric box at a known pose) and node configurations for it, one per input form.
//   make_test_data OUT_DIR
#include <filesystem>
#include <fstream>
#include <iostream>

#include "test_support.h"

namespace {

constexpr char kObject[] = R"(objects:
  - name: box
    id: 1
    model: synthetic/models/obj_000001.ply
model_cache: cache
)";

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: " << argv[0] << " OUT_DIR\n";
    return 2;
  }
  const std::filesystem::path out = argv[1];
  std::filesystem::remove_all(out);
  std::filesystem::create_directories(out);
  stocs::test::writeSyntheticBopDataset(out / "synthetic");
  // Organized cloud and one probability image per object: the config defaults.
  std::ofstream(out / "synthetic.yaml") << kObject;
  // The same, for the bad-inputs test, which rewrites it to exercise ~reload.
  std::ofstream(out / "reloadable.yaml") << kObject;
  // Depth image + camera_info, one multi-channel image with an ignored background channel, and
  // boundary maps.
  std::ofstream(out / "synthetic_multichannel.yaml")
      << kObject << "input:\n  source: depth\n  probability: multichannel\n"
      << "  channels: [\"-\", box]\n  boundary: true\n";
  return 0;
}
