// The node's configuration file: config/default.yaml says the truth about the defaults, every key
// reaches its field, paths resolve, and each kind of mistake is reported with its file, key and
// problem.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "stocs/util/error.h"
#include "stocs/util/param_docs.h"
#include "stocs_ros/common/node_config.h"
#include "test_support.h"

namespace stocs_ros {
namespace {

std::filesystem::path writeConfig(const std::string& text) {
  const std::filesystem::path dir = stocs::test::scratchDir("config");
  std::ofstream(dir / "node.yaml") << text;
  return dir / "node.yaml";
}

/// The message of the InputError that loading `text` throws ("" when it loads).
std::string loadError(const std::string& text) {
  try {
    loadNodeConfig(writeConfig(text));
  } catch (const stocs::InputError& e) {
    return e.what();
  }
  return "";
}

constexpr char kBox[] = "objects:\n  - name: box\n    model: box.ply\n";

TEST(NodeConfig, DefaultFileHoldsTheCoreDefaults) {
  const NodeConfig c = loadNodeConfig("config/default.yaml", "/data/lmo-cat");
  ASSERT_EQ(c.objects.size(), 1u);
  EXPECT_EQ(c.objects[0].name, "cat");
  EXPECT_EQ(c.objects[0].id, 6);
  EXPECT_EQ(c.objects[0].model, "/data/lmo-cat/models/obj_000006.ply");
  EXPECT_FLOAT_EQ(c.objects[0].unit_scale, 0.001f);
  EXPECT_TRUE(c.objects[0].mesh_url.empty());
  EXPECT_TRUE(c.objects[0].symmetries.empty());

  EXPECT_EQ(c.model_cache, stocs::ModelCache::defaultDirectory());
  // Every other key of the file holds its field's default.
  const stocs::DescribedParams loaded = NodeConfig::schema().describe(c);
  const stocs::DescribedParams defaults = NodeConfig::schema().describe(NodeConfig());
  ASSERT_EQ(loaded.size(), defaults.size());
  for (size_t i = 0; i < loaded.size(); ++i) {
    EXPECT_EQ(loaded[i].second, defaults[i].second) << loaded[i].first.key;
  }
}

// rviz draws an OBJ, STL, DAE, glTF or GLB model from the model file itself, in the frame the
// estimator reads it in; PLY and PCD models are drawn as points unless `mesh` is set.
TEST(NodeConfig, AMeshFormatModelIsDrawnFromItsOwnFile) {
  const std::filesystem::path file = writeConfig(
      "objects:\n  - {name: arm, model: urdf/../meshes/arm.DAE, unit_scale: 1}\n"
      "  - {name: cup, model: cup.stl, mesh: cup_visual.dae}\n  - {name: box, model: box.ply}\n");
  const NodeConfig c = loadNodeConfig(file);
  const std::filesystem::path dir = file.parent_path();
  EXPECT_EQ(c.objects[0].mesh_url, "file://" + (dir / "meshes/arm.DAE").string());
  EXPECT_FLOAT_EQ(c.objects[0].mesh_scale, 1.0f);
  EXPECT_EQ(c.objects[1].mesh_url, "file://" + (dir / "cup_visual.dae").string());
  EXPECT_TRUE(c.objects[2].mesh_url.empty());
}

TEST(NodeConfig, ValuesReachTheirFieldsAndPathsResolve) {
  const std::filesystem::path file = writeConfig(R"(objects:
  - name: box
    id: 7
    model: models/box.ply
    unit_scale: 0.01
    mesh: package://stocs_ros/config/box.dae
    symmetries:
      discrete: [[-1, 0, 0, 10,  0, -1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]]
      continuous: [{axis: [0, 0, 2], offset: [0, 5, 0]}]
  - name: can_2
    model: /abs/can.ply
    mesh: meshes/can.stl
input:
  source: depth
  probability: multichannel
  channels: ["-", can_2, box]
  uint16_scale: 1000
  boundary: true
  sync: {tolerance: 0.05, queue_size: 4, max_age: 0}
output: {frame_prefix: "est_", tf: false, markers: false, estimate_on_frames: false}
model_cache: none
estimation:
  segment: {min_probability: 0.3, samples_per_voxel: 0, normals: {radius: 0.02}}
  model: {ppf: {angle_step_deg: 12}}
  stocs: {bases: 40, base_draw_budget: 120, focused_bases: 3, base: {focus_exponent: 2}, consensus_bases: 6, seed: 9, instances: 4,
          instance_separation: 0.2, min_normal_agreement: 2,
          finished_per_base: 7, icp: {enabled: false, candidates: 3, screening_iterations: 4, finalists: 3}, free_space: {enabled: false, margin: 0.02},
          lcp: {distance: 0.004, coarse_fraction: 0.5, coarse_ratio: 0.3}}
)");
  const NodeConfig c = loadNodeConfig(file);
  const std::filesystem::path dir = file.parent_path();
  ASSERT_EQ(c.objects.size(), 2u);
  const ObjectConfig& box = c.objects[0];
  EXPECT_EQ(box.id, 7);
  EXPECT_EQ(box.model, dir / "models/box.ply");
  EXPECT_FLOAT_EQ(box.unit_scale, 0.01f);
  EXPECT_FLOAT_EQ(box.mesh_scale, 0.01f);
  EXPECT_EQ(box.mesh_url, "package://stocs_ros/config/box.dae");
  ASSERT_EQ(box.symmetries.discrete.size(), 1u);
  EXPECT_TRUE(box.symmetries.discrete[0].translation().isApprox(Eigen::Vector3f(0.1f, 0, 0)));
  ASSERT_EQ(box.symmetries.continuous.size(), 1u);
  EXPECT_TRUE(box.symmetries.continuous[0].axis.isApprox(Eigen::Vector3f::UnitZ()));
  EXPECT_TRUE(box.symmetries.continuous[0].offset.isApprox(Eigen::Vector3f(0, 0.05f, 0)));
  EXPECT_EQ(c.objects[1].id, 2);  // default: position + 1
  EXPECT_EQ(c.objects[1].model, "/abs/can.ply");
  EXPECT_EQ(c.objects[1].mesh_url, "file://" + (dir / "meshes/can.stl").string());
  EXPECT_EQ(c.objectIndex("can_2"), 1);
  EXPECT_EQ(c.objectIndex("cup"), -1);

  EXPECT_EQ(c.input.depth, DepthSource::kDepthImage);
  EXPECT_EQ(c.input.probability, ProbabilitySource::kMultichannel);
  EXPECT_EQ(c.input.channels, (std::vector<std::string>{"-", "can_2", "box"}));
  EXPECT_EQ(c.input.uint16_scale, 1000);
  EXPECT_TRUE(c.input.boundary);
  EXPECT_EQ(c.input.sync.tolerance, 0.05);
  EXPECT_EQ(c.input.sync.queue_size, 4);
  EXPECT_EQ(c.input.sync.max_age, 0);
  EXPECT_EQ(c.output.frame_prefix, "est_");
  EXPECT_FALSE(c.output.tf || c.output.markers || c.output.estimate_on_frames);
  EXPECT_TRUE(c.model_cache.empty());
  EXPECT_FLOAT_EQ(c.estimation.segment.min_probability, 0.3f);
  EXPECT_EQ(c.estimation.segment.samples_per_voxel, 0.0f);
  EXPECT_FLOAT_EQ(c.estimation.segment.normals.radius, 0.02f);
  EXPECT_FLOAT_EQ(c.estimation.model.ppf.angle_step_deg, 12.0f);
  EXPECT_EQ(c.estimation.stocs.bases, 40);
  EXPECT_EQ(c.estimation.stocs.seed, 9u);
  EXPECT_FALSE(c.estimation.stocs.icp.enabled);
  EXPECT_FLOAT_EQ(c.estimation.stocs.lcp.distance, 0.004f);
  EXPECT_FLOAT_EQ(c.estimation.stocs.lcp.coarse_fraction, 0.5f);
  EXPECT_FLOAT_EQ(c.estimation.stocs.lcp.coarse_ratio, 0.3f);
  EXPECT_EQ(c.estimation.stocs.icp.candidates, 3);
  EXPECT_EQ(c.estimation.stocs.icp.screening_iterations, 4);
  EXPECT_EQ(c.estimation.stocs.icp.finalists, 3);
  EXPECT_FALSE(c.estimation.stocs.free_space.enabled);
  EXPECT_FLOAT_EQ(c.estimation.stocs.free_space.margin, 0.02f);
  EXPECT_EQ(c.estimation.stocs.instances, 4);
  EXPECT_FLOAT_EQ(c.estimation.stocs.instance_separation, 0.2f);
  EXPECT_EQ(c.estimation.stocs.min_normal_agreement, 2);
  EXPECT_EQ(c.estimation.stocs.finished_per_base, 7);
  EXPECT_EQ(c.estimation.stocs.consensus_bases, 6);
  EXPECT_EQ(c.estimation.stocs.base_draw_budget, 120);
  EXPECT_EQ(c.estimation.stocs.focused_bases, 3);
  EXPECT_EQ(c.estimation.stocs.base.focus_exponent, 2);
}

TEST(NodeConfig, DatasetPathsResolveInsideTheGivenDataset) {
  const std::filesystem::path file = writeConfig(
      "objects:\n  - {name: a, model: $(dataset)/models/a.ply, mesh: "
      "$(dataset)/meshes/a.stl}\nmodel_cache: $(dataset)/../cache\n");
  const NodeConfig c = loadNodeConfig(file, "/data/ycbv-0000");
  EXPECT_EQ(c.objects[0].model, "/data/ycbv-0000/models/a.ply");
  EXPECT_EQ(c.objects[0].mesh_url, "file:///data/ycbv-0000/meshes/a.stl");
  EXPECT_EQ(c.model_cache, "/data/ycbv-0000/../cache");
}

TEST(NodeConfig, ClassIdsComeFromInputLabelsOrTheObjectIds) {
  const std::string objects =
      "objects:\n  - {name: a, id: 7, model: a.ply}\n  - {name: b, model: b.ply}\n";
  const NodeConfig by_id = loadNodeConfig(writeConfig(objects + "input: {probability: masks}\n"));
  EXPECT_EQ(by_id.classOf(0), 7);
  EXPECT_EQ(by_id.classOf(1), 2);
  const NodeConfig by_list =
      loadNodeConfig(writeConfig(
          objects + "input: {probability: labels, labels: [\"-\", b, a], label_confidence: true,\n"
                    "        segmentation: {mask_border_px: 5}}\n"));
  EXPECT_EQ(by_list.classOf(0), 2);
  EXPECT_EQ(by_list.classOf(1), 1);
  EXPECT_TRUE(by_list.input.label_confidence);
  EXPECT_EQ(by_list.input.segmentation.mask_border_px, 5.0f);
}

// A BOP model's symmetries come from the models_info.json beside it; a file that is not one names
// itself and the object.
TEST(NodeConfig, SymmetriesComeFromTheModelsInfoBesideABopModel) {
  const std::filesystem::path dir = stocs::test::scratchDir("config_models_info");
  const std::filesystem::path config = dir / "node.yaml";
  std::ofstream(config) << "objects:\n  - {name: bowl, model: obj_000005.ply}\n";
  std::ofstream(dir / "obj_000005.ply") << "ply\n";  // read when the node loads it, not here
  std::ofstream(dir / "models_info.json")
      << R"({"5": {"diameter": 150, "symmetries_continuous": [{"axis": [0, 0, 1], )"
      << R"("offset": [0, 0, 0]}]}})";
  const NodeConfig c = loadNodeConfig(config);
  ASSERT_EQ(c.objects[0].symmetries.continuous.size(), 1u);
  EXPECT_TRUE(c.objects[0].symmetries.continuous[0].axis.isApprox(Eigen::Vector3f::UnitZ()));

  std::ofstream(dir / "models_info.json") << R"({"5": {"diameter": 150, "symmetries_continuous")";
  try {
    loadNodeConfig(config);
    ADD_FAILURE() << "a malformed models_info.json was read";
  } catch (const stocs::InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("objects[0]"), std::string::npos) << message;
    EXPECT_NE(message.find("symmetries from models_info.json"), std::string::npos) << message;
    EXPECT_NE(message.find("models_info.json"), std::string::npos) << message;
  }
}

TEST(NodeConfig, GeometricInputReadsItsSegmentationKeys) {
  const NodeConfig c = loadNodeConfig(writeConfig(
      std::string(kBox) +
      "input: {probability: geometric, geometric: {stride: 1, plane_min_area: 0.1}}\n"));
  EXPECT_EQ(c.input.probability, ProbabilitySource::kGeometric);
  EXPECT_EQ(c.input.geometric.stride, 1);
  EXPECT_FLOAT_EQ(c.input.geometric.plane_min_area, 0.1f);
  EXPECT_FLOAT_EQ(c.input.geometric.crease_angle_deg,
                  stocs::GeometricSegmentationParams().crease_angle_deg);
}

TEST(NodeConfig, MistakesNameTheFileTheKeyAndTheProblem) {
  const std::string box = kBox;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"objects: [\n", "invalid YAML"},
      {"objects: []\n", "'objects' must be a non-empty list"},
      {box + "estimation:\n  stocs:\n    basez: 3\n",
       "node.yaml:6: estimation.stocs.basez: unknown key"},
      {box + "input: {sync: {tolerance: soon}}\n",
       "input.sync.tolerance: expected a number, got 'soon'"},
      {box + "estimation: {stocs: {bases: 2.5}}\n", "estimation.stocs.bases: expected an integer"},
      {box + "estimation: {stocs: {bases: 0}}\n",
       "node.yaml:4: estimation.stocs.bases: 0 is outside [1, 1000000]"},
      {box + "estimation: {segment: {min_probability: 1.5}}\n",
       "estimation.segment.min_probability: 1.5 is outside [0, 1)"},
      {box + "estimation: {segment: {samples_per_voxel: 0.5}}\n",
       "estimation.segment.samples_per_voxel: 0.5 is outside 0 or [1, 100]"},
      {box + "estimation: {stocs: {instances: 0}}\n",
       "estimation.stocs.instances: 0 is outside [1, 100]"},
      {box + "estimation: {stocs: {min_normal_agreement: 5}}\n",
       "estimation.stocs.min_normal_agreement: 5 is outside [0, 4]"},
      {box + "estimation: {stocs: {finished_per_base: 0}}\n",
       "estimation.stocs.finished_per_base: 0 is outside [1, 100000]"},
      {box + "estimation: {stocs: {consensus_bases: -1}}\n",
       "estimation.stocs.consensus_bases: -1 is outside [0, 1000]"},
      {box + "estimation: {stocs: {base_draw_budget: -1}}\n",
       "estimation.stocs.base_draw_budget: -1 is outside [0, 1000000]"},
      {box + "estimation: {stocs: {focused_bases: -2}}\n",
       "estimation.stocs.focused_bases: -2 is outside [0, 1000000]"},
      {box + "estimation: {stocs: {base: {focus_exponent: 0}}}\n",
       "estimation.stocs.base.focus_exponent: 0 is outside [1, 16]"},
      {box + "input: {sync: {queue_size: 0}}\n", "input.sync.queue_size: 0 is outside [1, 1000]"},
      {box + "tracking: {max_gap: 0}\n", "tracking.max_gap: 0 s is outside (0, 3600]"},
      {box + "tracking: {enabled: yes please}\n",
       "tracking.enabled: expected true or false, got 'yes please'"},
      {box + "input: {source: laser}\n", "input.source: 'laser' is not one of cloud, depth"},
      {box + "input: {probability: multichannel, channels: [box, cup]}\n",
       "input.channels names 'cup', which is not a configured object (box)"},
      {box + "input: {probability: multichannel, channels: [\"-\"]}\n",
       "object 'box' has no channel in input.channels"},
      {box + "input: {channels: [box]}\n", "input.channels is only used with"},
      {box + "input: {probability: masks, labels: [\"-\", cup]}\n",
       "input.labels names 'cup', which is not a configured object (box)"},
      {box + "input: {probability: boxes, labels: [\"-\", \"-\"]}\n",
       "object 'box' has no class in input.labels"},
      {box + "input: {labels: [box]}\n", "input.labels is only used with"},
      {box + "input: {probability: masks, label_confidence: true}\n",
       "input.label_confidence is only used with input.probability: labels"},
      {box + "input: {probability: contours}\n",
       "input.probability: 'contours' is not one of per_object, multichannel, labels, masks, "
       "boxes"},
      {box + "input: {segmentation: {box_core: 1}}\n",
       "input.segmentation.box_core: 1 is outside [0, 1)"},
      {box + "input: {geometric: {stride: 0}}\n", "input.geometric.stride: 0 px is outside [1, 8]"},
      {box + "input: {geometric: {min_extent_share: 2, max_extent_share: 1.5}}\n",
       "node.yaml: input.geometric: min_extent_share 2 must be below max_extent_share 1.5"},
      {box + "output: {tf: maybe}\n", "output.tf: expected true or false, got 'maybe'"},
      {"objects:\n  - model: box.ply\n", "objects[0].name '' must start with a letter"},
      {"objects:\n  - name: my cat\n    model: cat.ply\n", "objects[0].name 'my cat'"},
      {"objects:\n  - name: box\n", "objects[0].model is missing"},
      {box + "  - name: box\n    model: other.ply\n", "objects[1] repeats the name 'box'"},
      {"objects:\n  - {name: a, id: 3, model: a.ply}\n  - {name: b, id: 3, model: b.ply}\n",
       "repeats the name 'b' or the id 3"},
      {"objects:\n  - {name: a, model: a.ply, colour: red}\n", "objects[0].colour: unknown key"},
      {"objects:\n  - {name: a, model: $(env STOCS_NO_SUCH_VARIABLE)/a.ply}\n",
       "objects[0].model: path '$(env STOCS_NO_SUCH_VARIABLE)/a.ply': environment variable "
       "STOCS_NO_SUCH_VARIABLE is not set"},
      {"objects:\n  - {name: a, model: $(dataset)/models/a.ply}\n",
       "node.yaml: objects[0].model: path '$(dataset)/models/a.ply' uses $(dataset), but no "
       "dataset was given: set the node's ~dataset parameter (launch argument dataset:=FOLDER)"},
      {"objects:\n  - {name: a, model: a.ply, mesh: $(dataset)/a.stl}\n",
       "objects[0].mesh: path '$(dataset)/a.stl' uses $(dataset)"},
      {"objects:\n  - {name: a, model: package://no_such_package/a.ply}\n",
       "ROS package 'no_such_package' is not found"},
      {"objects:\n  - {name: a, model: a.ply, symmetries: {discrete: [[1, 2, 3]]}}\n",
       "objects[0].symmetries.discrete[0]: expected a list of 16 numbers"},
      {"objects:\n  - {name: a, model: a.ply, symmetries: {discrete: [[2,0,0,0, 0,1,0,0, 0,0,1,0, "
       "0,0,0,1]]}}\n",
       "rotation part is not a rotation matrix"},
      {"objects:\n  - {name: a, model: a.ply, symmetries: {continuous: [{axis: [0, 0, 0]}]}}\n",
       "axis has zero length"},
  };
  for (const auto& [text, expected] : cases) {
    const std::string error = loadError(text);
    EXPECT_NE(error.find(expected), std::string::npos)
        << "config:\n"
        << text << "expected an error with '" << expected << "', got '" << error << "'";
  }
  EXPECT_EQ(loadError(box), "");
  try {
    loadNodeConfig("/no/such/file.yaml");
    ADD_FAILURE() << "a missing file loaded";
  } catch (const stocs::InputError& e) {
    EXPECT_STREQ(e.what(), "/no/such/file.yaml: cannot open the configuration file");
  }
}

}  // namespace
}  // namespace stocs_ros
