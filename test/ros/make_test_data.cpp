// Writes the generated data the ROS integration tests play: the one-image BOP dataset of the CLI
// test (an asymmetric box at a known pose) and node configurations for it, one per input form; and
// a copy with objects that are not in the frame, for the rejection test; and the demo's
// configuration with each segmentation input form and with maps from the depth alone (geometric),
// for the generated scene.
//   make_test_data OUT_DIR DEMO_CONFIG
#include <filesystem>
#include <fstream>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "stocs/geometry/mesh.h"
#include "stocs/io/bop_dataset.h"
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
  - name: noise
    id: 2
    model: absent/models/obj_000002.ply
  - name: lookalike
    id: 3
    model: absent/models/obj_000003.ply
model_cache: cache
)";

/// The box frame with two more objects that are not in it: "noise" (a flat plate), whose map is
/// low background noise with a few blobs, as a network could emit for an absent object; and
/// "lookalike", the box 10% smaller, whose map marks the present box at 70% of the box's own (a
/// network's class confusion), which the frame-level explanation gives to the box.
void writeAbsentObjects(const std::filesystem::path& root) {
  stocs::test::writeSyntheticBopDataset(root);
  const stocs::MeshData plate = stocs::boxMesh(Eigen::Vector3f(0.12f, 0.09f, 0.01f));
  const stocs::MeshData box = stocs::asymmetricMesh();
  stocs::MeshData lookalike = box;
  for (Eigen::Vector3f& v : lookalike.vertices) v *= 0.9f;
  stocs::writePly(root / "models" / "obj_000002.ply", plate, 1000.0f);
  stocs::writePly(root / "models" / "obj_000003.ply", lookalike, 1000.0f);
  std::ofstream(root / "models" / "models_info.json")
      << R"({"1": {"diameter": )" << stocs::pointSetDiameter(box.vertices) * 1000
      << R"(}, "2": {"diameter": )" << stocs::pointSetDiameter(plate.vertices) * 1000
      << R"(}, "3": {"diameter": )" << stocs::pointSetDiameter(lookalike.vertices) * 1000 << "}}";
  const std::filesystem::path prob = root / "test" / "000000" / "prob";
  const cv::Mat present = cv::imread((prob / "000000_000001.png").string(), cv::IMREAD_UNCHANGED);
  cv::imwrite((prob / "000000_000003.png").string(), present * 0.7);
  cv::Mat noise(present.size(), CV_16UC1);
  cv::RNG random(5);
  random.fill(noise, cv::RNG::UNIFORM, 0, 3000);
  for (const cv::Point blob : {cv::Point(40, 40), cv::Point(280, 200), cv::Point(60, 190)}) {
    cv::circle(noise, blob, 5, cv::Scalar(6000), cv::FILLED);
  }
  cv::imwrite((prob / "000000_000002.png").string(), noise);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: " << argv[0] << " OUT_DIR DEMO_CONFIG\n";
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
  // Poses in the robot's frame (robot_frame.test), and in a frame TF does not know.
  std::ofstream(out / "synthetic_base_link.yaml") << kObject << "output:\n  frame: base_link\n";
  std::ofstream(out / "synthetic_nowhere.yaml")
      << kObject << "output:\n  frame: nowhere\n  transform_timeout: 0.05\n";
  writeAbsentObjects(out / "absent");
  std::ofstream(out / "absent.yaml") << kAbsentObjects;
  // The same with detection in every frame, for the explanation outside tracking.
  std::ofstream(out / "absent_detection.yaml") << kAbsentObjects << "tracking:\n  enabled: false\n";
  const std::string demo = stocs::readTextFile(argv[2]);
  for (const char* form : {"labels", "masks", "boxes", "geometric"}) {
    std::ofstream(out / (std::string("synth_scene_") + form + ".yaml"))
        << demo << "\ninput:\n  probability: " << form << "\n";
  }
  return 0;
}
