// `stocs simmaps` (simulated_maps.h): a dataset without maps made playable as a sequence, in a new
// folder linking to the source, with a map for every target, the targets file and frame times;
// the source untouched; the same maps for a seed; bad requests refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "stocs/io/bop_dataset.h"
#include "stocs/io/bop_targets.h"
#include "stocs/sim/sequence_info.h"
#include "stocs/sim/simulated_maps.h"
#include "stocs/sim/synthetic_dataset.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {
namespace fs = std::filesystem;

/// Three generated views of one scene whose prob/ maps and targets are taken away.
fs::path datasetWithoutMaps() {
  const fs::path root = test::scratchDir("simmaps_source");
  SyntheticDatasetParams p;
  p.images_per_scene = 3;
  p.layout.objects = 3;
  p.camera = {307.5, 307.5, 159.5, 119.5, 320, 240};
  p.seed = 2;
  writeSyntheticDataset(root, p);
  fs::remove_all(root / "test" / "000000" / "prob");
  fs::remove(root / "test_targets_bop19.json");
  return root;
}

TEST(SimulatedMaps, EveryTargetGetsAMapAndTheImagesATime) {
  const fs::path source = datasetWithoutMaps();
  const fs::path out = test::scratchDir("simmaps_out");
  SimulatedMapsParams params;
  params.absent_per_image = 2;
  params.rate_hz = 15;
  writeSimulatedMapsDataset(source, out, params);
  EXPECT_TRUE(fs::is_symlink(out / "models"));
  EXPECT_TRUE(fs::is_symlink(out / "test" / "000000" / "depth"));
  EXPECT_FALSE(fs::exists(source / "test" / "000000" / "prob"));
  const BopDataset ds(out);
  const std::map<int, std::vector<BopGtInstance>> gt = ds.sceneGroundTruth(0);
  const std::vector<BopTarget> targets = readBopTargets(out / "test_targets_bop19.json");
  ASSERT_EQ(targets.size(), 3u * 5u);  // three objects and two absent ones in each image
  int absent = 0;
  for (const BopTarget& t : targets) {
    const auto& instances = gt.at(t.im_id);
    const auto count = std::count_if(instances.begin(), instances.end(),
                                     [&](const BopGtInstance& g) { return g.obj_id == t.obj_id; });
    EXPECT_EQ(t.inst_count, count);
    absent += t.inst_count == 0;
    const cv::Mat probability = ds.loadProbability(0, t.im_id, t.obj_id);
    if (t.inst_count > 0) {
      EXPECT_GT(cv::countNonZero(probability > 0.5), 100);
    }
  }
  EXPECT_EQ(absent, 6);
  const SequenceInfo info = readSequenceInfo(sequenceInfoPath(ds.sceneDir(0)));
  EXPECT_DOUBLE_EQ(info.rate_hz, 15);
  EXPECT_NEAR(info.stamps.at(2), 2 / 15.0, 1e-6);
  EXPECT_TRUE(info.events.empty());

  const fs::path again = test::scratchDir("simmaps_again");
  writeSimulatedMapsDataset(source, again, params);
  for (const BopTarget& t : targets) {
    EXPECT_EQ(readTextFile(ds.probabilityPath(0, t.im_id, t.obj_id)),
              readTextFile(BopDataset(again).probabilityPath(0, t.im_id, t.obj_id)));
  }
}

TEST(SimulatedMaps, Ycbv0000BecomesAFiveFrameSequenceAndIsLeftAsItWas) {
  STOCS_REQUIRE_DATASETS(datasets);
  const fs::path source = datasets / "ycbv-0000";
  const fs::path out = test::scratchDir("simmaps_ycbv");
  writeSimulatedMapsDataset(source, out, {});
  EXPECT_FALSE(fs::exists(source / "test" / "000000" / "prob"));
  EXPECT_FALSE(fs::exists(source / "test_targets_bop19.json"));
  const BopDataset ds(out);
  const SequenceInfo info = readSequenceInfo(sequenceInfoPath(ds.sceneDir(0)));
  ASSERT_EQ(info.stamps.size(), 5u);
  EXPECT_DOUBLE_EQ(info.stamps.begin()->second, 0);
  EXPECT_EQ(info.stamps.begin()->first, 1);  // YCB-Video's ids start at 1
  EXPECT_NEAR(info.stamps.at(5), 4 / 30.0, 1e-6);
  // Three objects per frame and two absent ones, each with a map that marks a present object.
  const std::vector<BopTarget> targets = readBopTargets(out / "test_targets_bop19.json");
  ASSERT_EQ(targets.size(), 25u);
  const std::map<int, std::vector<BopGtInstance>> gt = ds.sceneGroundTruth(0);
  for (const BopTarget& t : targets) {
    const cv::Mat probability = ds.loadProbability(0, t.im_id, t.obj_id);
    if (t.inst_count == 0) continue;
    const int instance = static_cast<int>(
        std::find_if(gt.at(t.im_id).begin(), gt.at(t.im_id).end(),
                     [&](const BopGtInstance& g) { return g.obj_id == t.obj_id; }) -
        gt.at(t.im_id).begin());
    const cv::Mat mask =
        cv::imread(ds.maskVisibPath(0, t.im_id, instance).string(), cv::IMREAD_GRAYSCALE);
    EXPECT_GT(cv::mean(probability, mask)[0], 0.5) << "image " << t.im_id << " object " << t.obj_id;
  }
}

TEST(SimulatedMaps, BadRequestsAreRefused) {
  const fs::path source = datasetWithoutMaps();
  const fs::path out = test::scratchDir("simmaps_bad");
  std::ofstream(out / "keep.txt") << "user data";
  EXPECT_THROW(writeSimulatedMapsDataset(source, out, {}), InputError);
  EXPECT_TRUE(fs::exists(out / "keep.txt"));
  SimulatedMapsParams params;
  params.segmentation_preset = "wild";
  EXPECT_THROW(writeSimulatedMapsDataset(source, out / "a", params), InputError);
  params = {};
  params.absent_per_image = -1;
  EXPECT_THROW(writeSimulatedMapsDataset(source, out / "b", params), InputError);
  params = {};
  params.rate_hz = 0;
  EXPECT_THROW(writeSimulatedMapsDataset(source, out / "c", params), InputError);
  EXPECT_THROW(writeSimulatedMapsDataset(out / "none", out / "d", {}), InputError);
  EXPECT_FALSE(fs::exists(out / "a"));
}

}  // namespace
}  // namespace stocs
