// The node, the scene publisher and the segmentation node started with bad configurations or
// parameters: each exits with code 1 and a message naming the problem (run under rostest for the
// ROS master they need).
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "test_support.h"

namespace stocs_ros::test {
namespace {

constexpr char kObject[] = "objects:\n  - name: box\n    model: box.ply\n";

/// A node name of its own for each run: private parameters stay on the parameter server after a
/// run.
std::string nextNodeName() {
  static int runs = 0;
  return "probe_" + std::to_string(++runs);
}

/// Runs `executable` as node `name` with ROS arguments; `timeout` ends it if it wrongly keeps
/// running.
int run(const std::string& executable, const std::string& args, std::string& output,
        const std::string& name = nextNodeName()) {
  return stocs::test::runCommand("timeout 60 " + executable + " __name:=" + name + " " + args,
                                 output);
}

void expectNodeFails(const std::filesystem::path& config, const std::string& expected,
                     const std::string& args = "") {
  std::string output;
  EXPECT_EQ(run(STOCS_NODE_PATH, "_config:=" + config.string() + " " + args, output), 1) << output;
  EXPECT_NE(output.find(expected), std::string::npos) << "expected '" << expected << "' in:\n"
                                                      << output;
}

std::filesystem::path writeConfig(const std::filesystem::path& dir, const std::string& name,
                                  const std::string& text) {
  std::ofstream(dir / name) << text;
  return dir / name;
}

TEST(BadConfig, NodeExitsWithAMessageNamingTheProblem) {
  const std::filesystem::path dir = stocs::test::scratchDir("configs");
  stocs::writePly(dir / "box.ply", stocs::boxMesh({60, 40, 30}));

  expectNodeFails(dir / "missing.yaml", "cannot open the configuration file");
  expectNodeFails(writeConfig(dir, "broken.yaml", "objects: [\n"), "invalid YAML");
  expectNodeFails(writeConfig(dir, "unknown_key.yaml",
                              std::string(kObject) + "estimation:\n  stocs:\n    basez: 3\n"),
                  "estimation.stocs.basez: unknown key");
  expectNodeFails(writeConfig(dir, "out_of_range.yaml",
                              std::string(kObject) + "estimation: {stocs: {bases: 0}}\n"),
                  "estimation.stocs.bases: 0 is outside [1, 1000000]");
  expectNodeFails(writeConfig(dir, "wrong_type.yaml",
                              std::string(kObject) + "input: {sync: {tolerance: soon}}\n"),
                  "input.sync.tolerance: expected a number, got 'soon'");
  expectNodeFails(
      writeConfig(dir, "no_model.yaml", "objects:\n  - name: box\n    model: nowhere.ply\n"),
      "object 'box': model " + (dir / "nowhere.ply").string());
  expectNodeFails(writeConfig(dir, "no_objects.yaml", "objects: []\n"),
                  "'objects' must be a non-empty list");
  // Models named inside the dataset the launch files pass (config/default.yaml does).
  const std::filesystem::path in_dataset = writeConfig(
      dir, "in_dataset.yaml", "objects:\n  - name: box\n    model: $(dataset)/box.ply\n");
  expectNodeFails(in_dataset,
                  "objects[0].model: path '$(dataset)/box.ply' uses $(dataset), but no dataset "
                  "was given: set the node's ~dataset parameter");
  expectNodeFails(in_dataset, "object 'box': model /no/such/dataset/box.ply: no such file",
                  "_dataset:=/no/such/dataset");

  std::ofstream(dir / "empty.ply").flush();
  expectNodeFails(
      writeConfig(dir, "empty_model.yaml", "objects:\n  - name: box\n    model: empty.ply\n"),
      "model " + (dir / "empty.ply").string() + ": file is empty");
  std::ofstream(dir / "garbage.ply") << "this is not a ply file\n";
  expectNodeFails(
      writeConfig(dir, "garbage_model.yaml", "objects:\n  - name: box\n    model: garbage.ply\n"),
      "model " + (dir / "garbage.ply").string() + ": not a PLY file");
  // box.ply is in millimetres (60 mm long); declared as metres it would be 60 m long.
  expectNodeFails(
      writeConfig(dir, "unit_mistake.yaml", std::string(kObject) + "    unit_scale: 1\n"),
      "is implausible for an object; is the unit scale right? (BOP models are in mm: "
      "use 0.001)");

  std::string output;
  EXPECT_EQ(run(STOCS_NODE_PATH, "", output), 1) << output;
  EXPECT_NE(output.find("config (the configuration file) is not set"), std::string::npos) << output;
}

TEST(BadConfig, ScenePublisherExitsWithAMessageNamingTheProblem) {
  const std::filesystem::path dir = stocs::test::scratchDir("publisher");
  const std::filesystem::path config = writeConfig(dir, "config.yaml", kObject);
  std::string output;
  EXPECT_EQ(
      run(SCENE_PUBLISHER_PATH, "_config:=" + config.string() + " _dataset:=/nonexistent", output),
      1);
  EXPECT_NE(output.find("/nonexistent"), std::string::npos) << output;

  const std::filesystem::path data = dir / "data";
  stocs::test::writeSyntheticBopDataset(data);
  const std::string args = "_config:=" + config.string() + " _dataset:=" + data.string();
  EXPECT_EQ(run(SCENE_PUBLISHER_PATH, args + " _rate:=-1.0", output), 1) << output;
  EXPECT_NE(output.find("rate -1 Hz is outside 0 or (0, 100]"), std::string::npos) << output;
  // At rate 0 (the sequence's own), a sequence's scene_events.json is read.
  const std::filesystem::path events = data / "test" / "000000" / "scene_events.json";
  std::ofstream(events) << R"({"rate_hz": 0, "events": [], "stamps": {"0": 0}})";
  EXPECT_EQ(run(SCENE_PUBLISHER_PATH, args + " _rate:=0", output), 1) << output;
  EXPECT_NE(output.find(events.string() + ": rate_hz 0 is not a positive frame rate"),
            std::string::npos)
      << output;
  std::filesystem::remove(events);
  EXPECT_EQ(run(SCENE_PUBLISHER_PATH, args + " _probability_source:=network", output), 1) << output;
  EXPECT_NE(
      output.find("parameter probability_source 'network': unknown probability source 'network'; "
                  "known: 'real'"),
      std::string::npos)
      << output;
  EXPECT_NE(output.find("'sim:PRESET'"), std::string::npos) << output;
  EXPECT_EQ(run(SCENE_PUBLISHER_PATH, args + " _probability_source:=sim:wild", output), 1)
      << output;
  EXPECT_NE(
      output.find("parameter probability_source 'sim:wild': unknown segmentation preset 'wild'; "
                  "known presets: "),
      std::string::npos)
      << output;
  // roscpp reads `_scenes:=4` as an integer, not a list.
  EXPECT_EQ(run(SCENE_PUBLISHER_PATH, args + " _scenes:=4", output), 1) << output;
  EXPECT_NE(output.find("scenes must be a list of integers"), std::string::npos) << output;
  // A list comes from the parameter server, as roslaunch sets it.
  const std::string name = nextNodeName();
  ros::param::set("/" + name + "/scenes", std::vector<int>{4});
  EXPECT_EQ(run(SCENE_PUBLISHER_PATH, args, output, name), 1) << output;
  EXPECT_NE(output.find("scene 4 does not exist"), std::string::npos) << output;
}

TEST(BadConfig, SegmentationNodeExitsWithAMessageNamingTheProblem) {
  struct Case {
    std::string args;                   ///< scalar private parameters
    std::vector<std::string> channels;  ///< set on the parameter server (roscpp's _x:= are scalars)
    std::string expected;
  };
  const std::string model = std::string(" _model:=") + SEGMENTER_MODEL;
  const std::vector<std::string> seven = {"a", "b", "c", "d", "e", "f", "g"};
  for (const Case& c : std::vector<Case>{
           {" _model:=/nonexistent/m.onnx", seven,
            "segmentation model /nonexistent/m.onnx: no such file"},
           {model + " _classes:=3",
            {"a", "b", "c"},
            "output shape [1, 7, 120, 160] is not NCHW with 3 classes"},
           {model, {}, "must name the object of each output channel"},
           {"", seven, "/model is not set"},
           {model + " _classes:=3", seven, "channels names 7 channels, but classes is 3"},
           {model,
            {"-", "1", "b", "c", "d", "e", "f"},
            "/channels names '1', which is not a ROS topic name"},
           {model + " _resize:=crop", seven, "is 'crop', not one of stretch, letterbox"},
           {model + " _input_width:=wide", seven, "/input_width must be an integer"},
           {model + " _input_width:=0", seven, "/input_width 0 px is outside [8, 8192]"},
           {model + " _probability_depth:=16U", seven,
            "/probability_depth is '16U', not one of 32F, 8U"}}) {
    const std::string name = nextNodeName();
    if (!c.channels.empty()) ros::param::set("/" + name + "/channels", c.channels);
    std::string output;
    EXPECT_EQ(run(SEGMENTATION_NODE_PATH, c.args, output, name), 1) << c.args << "\n" << output;
    EXPECT_NE(output.find(c.expected), std::string::npos) << "expected '" << c.expected << "' in:\n"
                                                          << output;
  }
}

TEST(BadConfig, SegmentationNodeWarnsThatThePackagesNetworkKnowsOnlySixMeshes) {
  // The package's network by its path, and the same file copied elsewhere (someone's own network):
  // only the first is warned of. Each runs until `timeout` ends it (exit code 124).
  const std::filesystem::path own = stocs::test::scratchDir("own_network") / "mine.onnx";
  std::filesystem::copy_file(SEGMENTER_MODEL, own,
                             std::filesystem::copy_options::overwrite_existing);
  const std::string warning =
      "is the package's own network, trained on generated scenes of the "
      "project's 6 meshes (box, long_box, cylinder, mug, bowl, block) only";
  for (const std::string& model : {std::string(SEGMENTER_MODEL), own.string()}) {
    const std::string name = nextNodeName();
    ros::param::set(
        "/" + name + "/channels",
        std::vector<std::string>{"-", "box", "long_box", "cylinder", "mug", "bowl", "block"});
    std::string output;
    EXPECT_EQ(stocs::test::runCommand("timeout 10 " + std::string(SEGMENTATION_NODE_PATH) +
                                          " __name:=" + name + " _model:=" + model,
                                      output),
              124)
        << output;
    ASSERT_NE(output.find("waiting for subscribers"), std::string::npos) << output;
    EXPECT_EQ(output.find(warning) != std::string::npos, model == SEGMENTER_MODEL) << model << ":\n"
                                                                                   << output;
    // ... and it names what needs no network.
    EXPECT_EQ(output.find("give the StoCS node input.probability: geometric") != std::string::npos,
              model == SEGMENTER_MODEL)
        << output;
  }
}

TEST(BadConfig, ScenePublisherWarnsOfSimulatedTimeWithoutAClock) {
  // What a bag launch's use_sim_time:=true leaves on a long-running master; reset for the tests
  // after this one (this process read it at its start).
  ros::param::set("/use_sim_time", true);
  const std::filesystem::path dir = stocs::test::scratchDir("publisher_sim_time");
  const std::filesystem::path config = writeConfig(dir, "config.yaml", kObject);
  stocs::test::writeSyntheticBopDataset(dir / "data");
  std::string output;
  const int status = stocs::test::runCommand(
      "timeout 12 " + std::string(SCENE_PUBLISHER_PATH) + " __name:=" + nextNodeName() +
          " _config:=" + config.string() + " _dataset:=" + (dir / "data").string(),
      output);
  ros::param::set("/use_sim_time", false);
  EXPECT_EQ(status, 124) << output;
  EXPECT_NE(output.find("scene_publisher: /use_sim_time is true but no /clock message has "
                        "arrived in 5 s"),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("rosparam set /use_sim_time false"), std::string::npos) << output;
}

TEST(BadConfig, ScenePublisherWarnsOnceOfAFrameWithoutProbabilityMaps) {
  const std::filesystem::path dir = stocs::test::scratchDir("publisher");
  const std::filesystem::path config = writeConfig(dir, "config.yaml", kObject);
  const std::filesystem::path data = dir / "data";
  stocs::test::writeSyntheticBopDataset(data);
  std::filesystem::remove_all(data / "test" / "000000" / "prob");
  // It plays the frame in a loop until `timeout` ends it (exit code 124).
  std::string output;
  EXPECT_EQ(stocs::test::runCommand(
                "timeout 10 " + std::string(SCENE_PUBLISHER_PATH) + " __name:=" + nextNodeName() +
                    " _config:=" + config.string() + " _dataset:=" + data.string() + " _rate:=20",
                output),
            124)
      << output;
  const std::string warning = data.string() +
                              " has no probability map (prob/) for object 'box' (id 1) in scene 0 "
                              "image 0: its probability image is all zero";
  const size_t first = output.find(warning);
  ASSERT_NE(first, std::string::npos) << output;
  EXPECT_EQ(output.find(warning, first + 1), std::string::npos) << "warned twice:\n" << output;
  EXPECT_NE(output.find("set the parameter ~probability_source (launch argument "
                        "probability_source:=) to sim:PRESET, e.g. sim:mild"),
            std::string::npos)
      << output;
}

}  // namespace
}  // namespace stocs_ros::test

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_bad_config");
  return RUN_ALL_TESTS();
}
