// The package's own segmentation network (models/segmenter.onnx, scripts/train_segmenter.sh) on
// generated scenes of a seed it was not trained on (training used seeds 1001-1006): it loads with
// config/segmenter.yaml's settings (SegmentationNetworkParams' defaults) and segments every object
// above a pixel precision and recall floor; `stocs estimate --prob onnx:` names a bad model.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "stocs/eval/segmentation_metrics.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/segmentation/segmentation_network.h"
#include "stocs/sim/ground_truth_masks.h"
#include "test_support.h"

namespace stocs {
namespace {

const std::string kTool = STOCS_TOOL_PATH;
const char* kModel = "models/segmenter.onnx";

// Twelve views (four scenes of seed 7; the first is the one view this test once had): a good
// network misses a tenth of some object in about one view in six of this kind (docs/simulator.md,
// "Why the unit test changed"), so each object's recall is pooled over the views, with a higher
// floor than the one view had (0.9).
TEST(SegmenterModel, SegmentsEveryObjectOfUnseenGeneratedScenes) {
  const auto data = test::scratchDir("segmenter_model") / "data";
  std::string out;
  ASSERT_EQ(test::runCommand(kTool + " synth --quiet --out " + data.string() +
                                 " --objects 6 --distractors 2 --seed 7 --scenes 4 --images 3",
                             out),
            0)
      << out;
  SegmentationNetworkParams params;
  params.model = kModel;
  const SegmentationNetwork network(params);
  const BopDataset dataset(data);
  const GroundTruthMasks masks(dataset);
  std::map<int, PixelCounts> per_object;
  int views = 0;
  for (const int scene : dataset.sceneIds()) {
    for (const auto& [image, camera] : dataset.sceneCameras(scene)) {
      const cv::Mat bgr = cv::imread(dataset.rgbPath(scene, image).string(), cv::IMREAD_COLOR);
      const std::vector<cv::Mat> maps = network.segment(bgr);
      ASSERT_EQ(maps.size(), 7u);
      const SegmentationScene frame = masks.frame(scene, image);
      for (size_t i = 0; i < frame.obj_ids.size(); ++i) {
        const int obj = frame.obj_ids[i];
        per_object[obj] +=
            countSegmentPixels(maps[obj], frame.labels == static_cast<int>(i) + 1, 0.5f);
      }
      ++views;
    }
  }
  ASSERT_EQ(views, 12);
  ASSERT_EQ(per_object.size(), 6u);
  PixelCounts pooled;
  for (const auto& [obj, counts] : per_object) {
    EXPECT_GT(counts.recall(), 0.95) << "object " << obj;
    pooled += counts;
  }
  // Pooled: a distractor coloured almost like an object takes that object's label in some views,
  // as the simulator's look-alikes do.
  EXPECT_GT(pooled.precision(), 0.75);
}

TEST(SegmenterModel, EstimateNamesAMissingOrCorruptModel) {
  const auto root = test::scratchDir("segmenter_model_errors");
  test::writeSyntheticBopDataset(root / "data");
  std::ofstream(root / "corrupt.onnx") << "not a model";
  for (const auto& [model, message] : std::vector<std::pair<std::string, std::string>>{
           {(root / "none.onnx").string(), "none.onnx: no such file"},
           {(root / "corrupt.onnx").string(), "corrupt.onnx: not an ONNX model OpenCV reads"}}) {
    std::string out;
    EXPECT_NE(test::runCommand(kTool + " estimate --dataset " + (root / "data").string() +
                                   " --out " + (root / "r.csv").string() + " --prob onnx:" + model,
                               out),
              0);
    EXPECT_NE(out.find(message), std::string::npos) << out;
  }
}

/// config/segmenter.yaml's settings for the CLI: the model beside the file, channels as obj_ids.
std::string cliSettings(const std::string& channels, int classes = 7,
                        const std::string& extra = "") {
  return fmt::format(
      "model: {}\ninput_width: 160\ninput_height: 120\nresize: stretch\nchannel_order: rgb\n"
      "scale: 0.00392156862745098\noutput: logits\nactivation: softmax\nclasses: {}\n"
      "channels: [{}]\n{}",
      std::filesystem::absolute(kModel).string(), classes, channels, extra);
}

/// `stocs simstats --per-object` of the network given as `network` (a model or a settings file)
/// on the dataset, with the network's name taken out of the rows.
std::string networkRows(const std::filesystem::path& data, const std::filesystem::path& network) {
  std::string out;
  EXPECT_EQ(test::runCommand(kTool + " simstats --per-object --presets mild --seeds 1 --dataset " +
                                 data.string() + " --network " + network.string(),
                             out),
            0)
      << out;
  const std::string name = network.filename().string();
  for (size_t at = out.find(name); at != std::string::npos; at = out.find(name)) {
    out.replace(at, name.size(), "NETWORK");
  }
  return out;
}

TEST(SegmenterModel, ASettingsFileGivesTheNetworkItsSettings) {
  const auto root = test::scratchDir("segmenter_model_settings");
  std::string out;
  ASSERT_EQ(test::runCommand(kTool + " synth --quiet --out " + (root / "data").string() +
                                 " --objects 6 --distractors 2 --seed 7",
                             out),
            0)
      << out;
  std::ofstream(root / "same.yaml") << cliSettings("'-', '1', '2', '3', '4', '5', '6'");
  std::ofstream(root / "swapped.yaml") << cliSettings("'-', '2', '1', '3', '4', '5', '6'");
  const std::string defaults = networkRows(root / "data", kModel);
  EXPECT_NE(defaults.find("| network NETWORK, obj 1 |"), std::string::npos) << defaults;
  EXPECT_EQ(networkRows(root / "data", root / "same.yaml"), defaults);
  // Channels named by the BOP model files' stems, as train_segmenter.sh --models writes them.
  std::ofstream(root / "stems.yaml")
      << cliSettings("'-', obj_000001, obj_000002, obj_000003, obj_000004, obj_000005, obj_000006");
  EXPECT_EQ(networkRows(root / "data", root / "stems.yaml"), defaults);
  EXPECT_NE(networkRows(root / "data", root / "swapped.yaml"), defaults)
      << "the settings file's channels were not used";
}

TEST(SegmenterModel, EstimateNamesBadSettings) {
  const auto root = test::scratchDir("segmenter_model_bad_settings");
  test::writeSyntheticBopDataset(root / "data");
  const std::string ids = "'-', '1', '2', '3', '4', '5', '6'";
  for (const auto& [text, message] : std::vector<std::pair<std::string, std::string>>{
           {cliSettings(ids, 7, "treads: 2\n"), "bad.yaml:11: treads: unknown key"},
           {cliSettings(ids, 7, "threads: -1\n"), "bad.yaml:11: threads: -1 is outside [0, 256]"},
           {cliSettings("'-', '1', '2', '3', '4'", 5),
            "output shape [1, 7, 120, 160] is not NCHW with 5 classes"},
           {cliSettings("'-', box, long_box, cylinder, mug, bowl, block"),
            "bad.yaml: channels names 'box'; for a BOP dataset name each channel's obj_id or model "
            "file stem"}}) {
    std::ofstream(root / "bad.yaml") << text;
    std::string out;
    EXPECT_EQ(test::runCommand(kTool + " estimate --dataset " + (root / "data").string() +
                                   " --out " + (root / "r.csv").string() +
                                   " --prob onnx:" + (root / "bad.yaml").string(),
                               out),
              2)
        << out;
    EXPECT_NE(out.find(message), std::string::npos) << out;
  }
}

}  // namespace
}  // namespace stocs
