// Writes the generated data the ROS integration tests play: the one-image BOP dataset of the CLI
// test (an asymmetric box at a known pose) and node configurations for it, one per input form; and
// a copy with two objects that are not in the frame, for the rejection test.
//   make_test_data OUT_DIR
#include <filesystem>
#include <fstream>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "stocs/geometry/mesh.h"
#include "stocs/io/ply_writer.h"
#include "stocs/sim/shape_meshes.h"
#include "test_support.h"

namespace {

constexpr char kObject[] = R"(objects:
  - name: box
    id: 1
    model: synthetic/models/obj_000001.ply
model_cache: cache
)";

constexpr char kAbsentObjects[] = R"(objects:
  - name: box
    id: 1
    model: absent/models/obj_000001.ply
  - name: confused
    id: 2
    model: absent/models/obj_000002.ply
  - name: noise
    id: 3
    model: absent/models/obj_000003.ply
model_cache: cache
)";

/// The box frame with two more objects that are not in it, each with the map a network could emit
/// for it: "confused" (a cylinder) marks the box's region (class confusion), "noise" (a flat plate)
/// has low background noise with a few blobs.
void writeAbsentObjects(const std::filesystem::path& root) {
  stocs::test::writeSyntheticBopDataset(root);
  const std::vector<stocs::MeshData> meshes = {
      stocs::cylinderMesh(0.03f, 0.08f, 48), stocs::boxMesh(Eigen::Vector3f(0.12f, 0.09f, 0.01f))};
  std::ofstream info(root / "models" / "models_info.json");
  const stocs::MeshData box = stocs::asymmetricMesh();
  info << R"({"1": {"diameter": )" << stocs::pointSetDiameter(box.vertices) * 1000 << "}";
  for (size_t k = 0; k < meshes.size(); ++k) {
    const int id = static_cast<int>(k) + 2;
    stocs::writePly(root / "models" / ("obj_00000" + std::to_string(id) + ".ply"), meshes[k],
                    1000.0f);
    info << ", \"" << id << R"(": {"diameter": )"
         << stocs::pointSetDiameter(meshes[k].vertices) * 1000 << "}";
  }
  info << "}";
  const std::filesystem::path prob = root / "test" / "000000" / "prob";
  const cv::Mat present = cv::imread((prob / "000000_000001.png").string(), cv::IMREAD_UNCHANGED);
  cv::Mat confused = present * (7000.0 / 9000.0);
  cv::imwrite((prob / "000000_000002.png").string(), confused);
  cv::Mat noise(present.size(), CV_16UC1);
  cv::RNG random(5);
  random.fill(noise, cv::RNG::UNIFORM, 0, 3000);
  for (const cv::Point blob : {cv::Point(40, 40), cv::Point(280, 200), cv::Point(60, 190)}) {
    cv::circle(noise, blob, 5, cv::Scalar(6000), cv::FILLED);
  }
  cv::imwrite((prob / "000000_000003.png").string(), noise);
}

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
  writeAbsentObjects(out / "absent");
  std::ofstream(out / "absent.yaml") << kAbsentObjects;
  return 0;
}
