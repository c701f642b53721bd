// Generated confusions that fit (issue 45): look-alike pairs in the catalogue, absent targets whose
// map marks the present look-alike (in `stocs synth`'s prob/ and through `--prob simonly:PRESET`),
// packed bins whose ground truth holds every box, and default scenes unchanged byte for byte.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "stocs/estimation/pipeline.h"
#include "stocs/eval/pose_metrics.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/io/bop_targets.h"
#include "stocs/sim/bop_writer.h"
#include "stocs/sim/lookalikes.h"
#include "stocs/sim/object_catalogue.h"
#include "stocs/sim/probability_source.h"
#include "stocs/sim/scene_layout.h"
#include "stocs/sim/segmentation_simulator.h"
#include "stocs/sim/synthetic_dataset.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {
namespace fs = std::filesystem;

/// The side lengths of a mesh's bounding box, metres.
Eigen::Vector3f extents(const MeshData& mesh) {
  Eigen::AlignedBox3f box;
  for (const Eigen::Vector3f& v : mesh.vertices) box.extend(v);
  return box.sizes();
}

const CatalogueObject& byId(const std::vector<CatalogueObject>& objects, int id) {
  for (const CatalogueObject& o : objects) {
    if (o.id == id) return o;
  }
  throw std::runtime_error("no object " + std::to_string(id));
}

TEST(LookalikeCatalogue, PairsAreBoxesWithin20PercentAndACanTheSizeOfTheMugBody) {
  const std::vector<CatalogueObject> all = catalogueSelection("lookalike");
  const Lookalikes expected = {{1, {10}}, {10, {1}}, {4, {11}}, {11, {4}}};
  EXPECT_EQ(catalogueLookalikes(all), expected);
  const Eigen::Vector3f box = extents(byId(all, 1).mesh), small = extents(byId(all, 10).mesh);
  EXPECT_TRUE(boxesLookAlike(box, small));
  EXPECT_FALSE(boxesLookAlike(extents(byId(all, 2).mesh), small));  // the long box
  // The mug's body: its extent across the handle's plane (y) and its height; the can's the same
  // within 20%, the cylinder's not.
  const Eigen::Vector3f mug = extents(byId(all, 4).mesh), can = extents(byId(all, 11).mesh);
  const Eigen::Vector3f body(mug.y(), mug.y(), mug.z());
  EXPECT_TRUE(boxesLookAlike(body, can));
  EXPECT_FALSE(boxesLookAlike(extents(byId(all, 3).mesh), can));
  for (const char* other : {"standard", "textured", "all"}) {
    EXPECT_TRUE(catalogueLookalikes(catalogueSelection(other)).empty()) << other;
  }
}

TEST(Lookalikes, FileRoundTripsAndMalformedFilesAreRefused) {
  const fs::path dir = test::scratchDir("lookalike_files");
  const Lookalikes pairs = {{1, {10}}, {10, {1}}, {4, {11}}, {11, {4}}};
  writeLookalikes(dir / "l.json", pairs);
  EXPECT_EQ(test::fileBytes(dir / "l.json"), "{\"pairs\":[[1,10],[4,11]]}\n");
  EXPECT_EQ(readLookalikes(dir / "l.json"), pairs);
  EXPECT_TRUE(readLookalikes(dir / "none.json").empty());
  std::ofstream(dir / "bad.json") << "[1, 2]";
  test::expectInputError([&] { readLookalikes(dir / "bad.json"); }, "not a look-alike file");
  std::ofstream(dir / "same.json") << R"({"pairs": [[3, 3]]})";
  test::expectInputError([&] { readLookalikes(dir / "same.json"); },
                         "pair [3,3] is not two different positive object ids");
  // A models folder's malformed file ends `stocs synth --models` before anything is written.
  writeModels(dir, {objectCatalogue()[0]});
  fs::copy_file(dir / "same.json", dir / "lookalikes.json");
  test::expectInputError([&] { writeSyntheticDataset(dir / "out", SyntheticDatasetParams(), dir); },
                         "lookalikes.json: pair [3,3]");
  EXPECT_FALSE(fs::exists(dir / "out"));
}

/// A 120 x 100 scene: object 1 in the left square, object 3 in the right one.
SegmentationScene twoObjects() {
  SegmentationScene scene{cv::Mat(100, 120, CV_32SC1, cv::Scalar(0)), {1, 3}, {}};
  scene.labels(cv::Rect(10, 30, 40, 40)).setTo(1);
  scene.labels(cv::Rect(70, 30, 40, 40)).setTo(2);
  return scene;
}

TEST(LookalikeConfusion, AbsentMapMarksThePresentLookalikeAndNothingElseChanges) {
  const SegmentationScene plain = twoObjects();
  SegmentationScene with = plain;
  with.lookalikes = {{1, {10}}, {10, {1}}};
  const SegmentationNoiseParams mild = segmentationPreset("mild");
  const cv::Mat left = plain.labels == 1, right = plain.labels == 2, background = plain.labels == 0;
  for (uint64_t seed = 0; seed < 10; ++seed) {
    const cv::Mat map = simulateSegmentation(with, 10, mild, seed);
    // mild: 0.9 x 0.8 x 0.75..1.25 where found, less in missed regions.
    EXPECT_GT(cv::mean(map, left)[0], 0.45) << "seed " << seed;
    EXPECT_LT(cv::mean(map, right)[0], 0.1) << "seed " << seed;
    EXPECT_LT(cv::mean(map, background)[0], 0.1) << "seed " << seed;
    // The present objects' maps and an absent object without look-alikes are as before.
    for (int obj : {1, 3, 7}) {
      const cv::Mat before = simulateSegmentation(plain, obj, mild, seed);
      EXPECT_EQ(cv::norm(before, simulateSegmentation(with, obj, mild, seed), cv::NORM_INF), 0)
          << "object " << obj << " seed " << seed;
    }
  }
}

/// A generated dataset of the look-alike catalogue.
fs::path lookalikeDataset(const std::string& name, uint64_t seed, int bin_object = 0) {
  const fs::path root = test::scratchDir(name);
  SyntheticDatasetParams p;
  p.catalogue = "lookalike";
  p.scenes = 2;
  p.seed = seed;
  p.bin.object = bin_object;
  writeSyntheticDataset(root, p);
  return root;
}

/// The visible mask of ground-truth instance `i` of an image (255 or 0).
cv::Mat maskVisib(const BopDataset& ds, int scene, int im, size_t i) {
  return cv::imread(ds.maskVisibPath(scene, im, static_cast<int>(i)).string(),
                    cv::IMREAD_GRAYSCALE) > 0;
}

/// The mask of the visible instances of `objects` in an image.
cv::Mat visibleMask(const BopDataset& ds, int scene, int im, const std::set<int>& objects) {
  const std::vector<BopGtInstance> gt =
      ds.sceneGroundTruth(scene).at(im);  // a copy: the map is a temporary
  cv::Mat mask;
  for (size_t i = 0; i < gt.size(); ++i) {
    const cv::Mat m = maskVisib(ds, scene, im, i);
    if (mask.empty()) mask = cv::Mat::zeros(m.size(), CV_8UC1);
    if (objects.count(gt[i].obj_id)) mask |= m;
  }
  return mask;
}

TEST(LookalikeConfusion, SynthAndTheSimulatedSourceMapAnAbsentTargetOnItsLookalike) {
  const fs::path root = lookalikeDataset("lookalike_synth", 3);
  const BopDataset ds(root);
  const Lookalikes pairs = readLookalikes(lookalikesPath(root));
  ASSERT_EQ(pairs.size(), 4u);
  const std::unique_ptr<ProbabilitySource> simulated = makeProbabilitySource("simonly:mild", ds, 0);
  int fitting = 0;
  for (const BopTarget& t : readBopTargets(root / "test_targets_bop19.json")) {
    if (t.inst_count > 0 || !pairs.count(t.obj_id)) continue;
    const cv::Mat lookalike = visibleMask(ds, t.scene_id, t.im_id, pairs.at(t.obj_id));
    if (lookalike.empty() || cv::countNonZero(lookalike) < 100) continue;
    ++fitting;
    for (const cv::Mat& map : {ds.loadProbability(t.scene_id, t.im_id, t.obj_id),
                               simulated->load(t.scene_id, t.im_id, t.obj_id)}) {
      EXPECT_GT(cv::mean(map, lookalike)[0], 0.4) << "object " << t.obj_id << " image " << t.im_id;
      EXPECT_LT(cv::mean(map, lookalike == 0)[0], 0.1);
    }
  }
  EXPECT_GE(fitting, 2);
}

TEST(PackedBin, GroundTruthHoldsEveryBoxAndNoTwoOverlap) {
  const fs::path root = lookalikeDataset("packed_bin", 5, 1);
  const BopDataset ds(root);
  for (const auto& [im, gt] : ds.sceneGroundTruth(0)) {
    ASSERT_EQ(gt.size(), 8u) << "image " << im;  // the default 2 x 4 boxes
    for (size_t i = 0; i < gt.size(); ++i) {
      EXPECT_EQ(gt[i].obj_id, 1);
      EXPECT_GT(cv::countNonZero(maskVisib(ds, 0, im, i)), 100);
    }
  }
  for (const BopTarget& t : readBopTargets(root / "test_targets_bop19.json")) {
    EXPECT_EQ(t.inst_count, t.obj_id == 1 ? 8 : 0) << "object " << t.obj_id;
  }
  PackedBinParams bin;
  bin.object = 1;
  Rng rng(9);
  const std::vector<PlacedObject> placed =
      arrangePackedBin(1, catalogueSelection("standard")[0].mesh, bin, rng);
  ASSERT_EQ(placed.size(), 8u + 4u);  // the boxes and four walls
  for (size_t i = 0; i < 8; ++i) {
    EXPECT_EQ(placed[i].obj_id, 1);
    EXPECT_TRUE(footprintClear(placed, i, placed[i].pose, 0)) << "box " << i;
  }
}

/// The boxes of image 0 of a packed bin's `scene` (object 1) that `estimate`'s poses find: each
/// ground-truth box taken by at most one pose within ADD-S of 10% of the diameter.
int distinctRightBoxes(const BopDataset& ds, int scene, const PoseEstimate& estimate,
                       const ObjectModel& model) {
  std::vector<BopGtInstance> boxes = ds.sceneGroundTruth(scene).at(0);
  int right = 0;
  for (const InstancePose& pose : estimate.instances) {
    const RigidPose e{pose.pose.linear().cast<double>(), pose.pose.translation().cast<double>()};
    for (auto box = boxes.begin(); box != boxes.end(); ++box) {
      if (addsError(model.points, e, {box->R, box->t_mm / 1000.0}) < 0.1 * model.diameter) {
        boxes.erase(box);
        ++right;
        break;
      }
    }
  }
  return right;
}

TEST(PackedBin, BoundariesFromTheColourKeepBasesWithinOneBox) {
  // The boxes' level tops give the depth no step between them; the colour image shows the gaps.
  const fs::path root = lookalikeDataset("packed_bin_colour", 5, 1);
  const BopDataset ds(root);
  PipelineParams params;
  params.stocs.instances = 8;
  const PreparedModel model = prepareModelFile(ds.modelPath(1).string(), 0.001f, params.model);
  int with = 0, without = 0;
  for (int scene = 0; scene < 2; ++scene) {
    const cv::Mat depth = ds.loadDepth(scene, 0);
    const BopFrameCamera cam = ds.sceneCameras(scene).at(0);
    const CameraIntrinsics k = cam.intrinsics(depth.cols, depth.rows);
    const OrganizedCloud cloud = cloudFromDepth(depth, k, cam.depth_scale / 1000);
    const cv::Mat probability = ds.loadProbability(scene, 0, 1);
    const cv::Mat colour = ds.loadColour(scene, 0, depth.size());
    const auto found = [&](bool from_colour) {
      PipelineParams p = params;
      p.colour_boundaries.enabled = from_colour;
      const PoseEstimate e = detectObject(cloud, static_cast<float>(k.fx), probability, model, p,
                                          nullptr, &k, &colour);
      return distinctRightBoxes(ds, scene, e, model.model);
    };
    with += found(true);
    without += found(false);
  }
  EXPECT_GE(with, 12) << "of 16 boxes";
  EXPECT_GT(with, without);
}

TEST(PackedBin, UnknownObjectAndSequencesAreRefused) {
  const fs::path root = test::scratchDir("bad_bin");
  SyntheticDatasetParams p;
  p.bin.object = 99;
  test::expectInputError([&] { writeSyntheticDataset(root / "a", p); },
                         "--packed-bin 99: no such object among the models (1, 2, 3, 4, 5, 6)");
  EXPECT_FALSE(fs::exists(root / "a" / "models"));
  p.bin.object = 1;
  p.sequence.enabled = true;
  test::expectInputError([&] { writeSyntheticDataset(root / "b", p); },
                         "does not apply to a sequence");
}

/// FNV-1a over every file's relative path and bytes, in path order; paths starting with `skip`
/// (when not empty) left out.
std::string treeDigest(const fs::path& root, const std::string& skip = "") {
  uint64_t h = 0xcbf29ce484222325ull;
  const auto add = [&h](const std::string& bytes) {
    for (const char c : bytes) h = (h ^ static_cast<uint8_t>(c)) * 0x100000001b3ull;
    h = h * 0x100000001b3ull;  // the 0 byte that ends each part
  };
  for (const auto& [name, content] : test::treeFiles(root)) {
    if (!skip.empty() && name.rfind(skip, 0) == 0) continue;
    add(name);
    add(content);
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

TEST(LookalikeCatalogue, DefaultScenesAreUnchanged) {
  // Digests of `stocs synth --images 2 --objects 4 --distractors 1 --seed 7` (and `--catalogue
  // textured --images 1 ... --seed 4`) as written before look-alikes and bins existed (5872bf1);
  // the standard objects' model files have carried their plain colour since, so the first leaves
  // models/ out (ObjectCatalogue.CommittedMeshesAreWhatTheGeneratorWrites checks those).
  SyntheticDatasetParams p;
  p.images_per_scene = 2;
  p.layout.objects = 4;
  p.layout.distractors = 1;
  p.seed = 7;
  const fs::path standard = test::scratchDir("default_digest");
  writeSyntheticDataset(standard, p);
  EXPECT_EQ(treeDigest(standard, "models/"), "8730d59b89bd7017");
  EXPECT_FALSE(fs::exists(lookalikesPath(standard)));
  p.images_per_scene = 1;
  p.seed = 4;
  p.catalogue = "textured";
  const fs::path textured = test::scratchDir("textured_digest");
  writeSyntheticDataset(textured, p);
  EXPECT_EQ(treeDigest(textured), "c3436ea9728d7b05");
}

}  // namespace
}  // namespace stocs
