// Generated BOP datasets: readable by BopDataset, ground truth consistent with depth and masks,
// the same files for the same seed, and refusal of bad requests.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "stocs/io/bop_dataset.h"
#include "stocs/io/bop_targets.h"
#include "stocs/io/mesh_io.h"
#include "stocs/io/ply_writer.h"
#include "stocs/sim/bop_writer.h"
#include "stocs/sim/depth_renderer.h"
#include "stocs/sim/synthetic_dataset.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {
namespace fs = std::filesystem;

SyntheticDatasetParams smallDataset(uint64_t seed) {
  SyntheticDatasetParams p;
  p.images_per_scene = 2;
  p.layout.objects = 4;
  p.layout.distractors = 1;
  p.seed = seed;
  return p;
}

/// The ground-truth instances rendered at their poses: depth (m) and labels (1 + gt index).
DepthRenderer renderTruth(const BopDataset& ds, const std::vector<BopGtInstance>& gt,
                          const CameraIntrinsics& k) {
  DepthRenderer r(k);
  for (size_t i = 0; i < gt.size(); ++i) {
    Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
    pose.linear() = gt[i].R.cast<float>();
    pose.translation() = (gt[i].t_mm / 1000).cast<float>();
    r.draw(loadMesh(ds.modelPath(gt[i].obj_id).string(), 0.001f), pose, static_cast<int>(i) + 1);
  }
  return r;
}

TEST(SyntheticDataset, IsABopDatasetWithEveryFile) {
  const fs::path root = test::scratchDir("synth");
  int reports = 0;
  writeSyntheticDataset(root, smallDataset(1), {}, [&](const SyntheticImageReport& r) {
    EXPECT_EQ(r.scene_id, 0);
    EXPECT_EQ(r.im_id, reports++);
    EXPECT_EQ(r.objects, 4);
  });
  EXPECT_EQ(reports, 2);
  const BopDataset ds(root);
  EXPECT_EQ(ds.sceneIds(), std::vector<int>{0});
  const std::map<int, BopObjectInfo> info = ds.modelsInfo();
  ASSERT_EQ(info.size(), objectCatalogue().size());
  EXPECT_EQ(info.at(1).symmetries_discrete.size(), 3u);
  EXPECT_EQ(info.at(5).symmetries_continuous.size(), 1u);
  const std::map<int, BopFrameCamera> cameras = ds.sceneCameras(0);
  const std::map<int, std::vector<BopGtInstance>> gt = ds.sceneGroundTruth(0);
  ASSERT_EQ(cameras.size(), 2u);
  ASSERT_EQ(gt.size(), 2u);
  const nlohmann::json gt_info =
      nlohmann::json::parse(readTextFile(ds.sceneDir(0) / "scene_gt_info.json"));
  EXPECT_FALSE(fs::exists(ds.sceneDir(0) / "scene_handles.json"));  // no handled object
  for (const auto& [im, instances] : gt) {
    EXPECT_NEAR(cameras.at(im).K(0, 0), 615.0, 1e-9);
    EXPECT_DOUBLE_EQ(cameras.at(im).depth_scale, 0.1);
    const cv::Mat depth = ds.loadDepth(0, im);
    EXPECT_EQ(depth.size(), cv::Size(640, 480));
    EXPECT_GT(cv::countNonZero(depth), 640 * 480 / 2);
    EXPECT_EQ(cv::imread(ds.rgbPath(0, im).string()).type(), CV_8UC3);
    ASSERT_EQ(instances.size(), 4u);
    for (size_t i = 0; i < instances.size(); ++i) {
      EXPECT_TRUE(info.count(instances[i].obj_id));
      const cv::Mat mask =
          cv::imread(ds.maskVisibPath(0, im, static_cast<int>(i)).string(), cv::IMREAD_GRAYSCALE);
      const nlohmann::json& entry = gt_info.at(std::to_string(im)).at(i);
      EXPECT_EQ(entry.at("px_count_visib").get<int>(), cv::countNonZero(mask));
      EXPECT_LE(entry.at("px_count_visib").get<int>(), entry.at("px_count_all").get<int>());
      const cv::Mat probability = ds.loadProbability(0, im, instances[i].obj_id);
      EXPECT_GT(cv::mean(probability, mask)[0], 0.5) << "image " << im << " instance " << i;
    }
  }
}

TEST(SyntheticDataset, GroundTruthPosesMatchTheDepthAndTheMasks) {
  for (float noise : {0.0f, 1.0f}) {
    const fs::path root = test::scratchDir(noise > 0 ? "noisy" : "exact");
    SyntheticDatasetParams params = smallDataset(2);
    params.depth_noise_level = noise;
    writeSyntheticDataset(root, params);
    const BopDataset ds(root);
    for (const auto& [im, instances] : ds.sceneGroundTruth(0)) {
      const cv::Mat depth = ds.loadDepth(0, im);
      const DepthRenderer truth =
          renderTruth(ds, instances, ds.sceneCameras(0).at(im).intrinsics(depth.cols, depth.rows));
      std::vector<float> errors;
      for (size_t i = 0; i < instances.size(); ++i) {
        const cv::Mat mask =
            cv::imread(ds.maskVisibPath(0, im, static_cast<int>(i)).string(), cv::IMREAD_GRAYSCALE);
        // Distractors are not in the ground truth: they may hide more of an object than the
        // rendering of the ground truth alone shows, never less.
        const cv::Mat rendered = truth.labels() == static_cast<int>(i) + 1;
        EXPECT_GT(cv::countNonZero(mask & rendered), 0.99 * cv::countNonZero(mask)) << i;
        for (int v = 0; v < depth.rows; ++v) {
          for (int u = 0; u < depth.cols; ++u) {
            if (!mask.at<uint8_t>(v, u) || depth.at<uint16_t>(v, u) == 0) continue;
            errors.push_back(
                std::abs(depth.at<uint16_t>(v, u) * 1e-4f - truth.depth().at<float>(v, u)));
          }
        }
      }
      ASSERT_GT(errors.size(), 1000u);
      std::sort(errors.begin(), errors.end());
      const float median = errors[errors.size() / 2], p95 = errors[errors.size() * 95 / 100];
      if (noise == 0) {
        EXPECT_LT(errors.back(), 0.0002f);  // the 0.1 mm depth unit and the model's rounding
      } else {
        EXPECT_LT(median, 0.003f);
        EXPECT_LT(p95, 0.01f);
        EXPECT_GT(median, 0.0003f);  // noise is there
      }
    }
  }
}

/// Chromaticity (r and g over r + g + b) of an RGB colour.
Eigen::Vector2f chromaticity(const Eigen::Vector3f& rgb) {
  return Eigen::Vector2f(rgb[0], rgb[1]) / rgb.sum();
}

// The model files carry the colour the images show (a plain object's in every vertex), so that
// colour evidence on generated scenes reads what a user's coloured meshes would give.
TEST(SyntheticDataset, EachModelFileCarriesTheColourItsObjectShows) {
  const fs::path root = test::scratchDir("synth_colours");
  writeSyntheticDataset(root, smallDataset(5));
  const BopDataset ds(root);
  const cv::Mat rgb = cv::imread(ds.rgbPath(0, 0).string());
  const std::vector<BopGtInstance> instances = ds.sceneGroundTruth(0).at(0);
  for (size_t i = 0; i < instances.size(); ++i) {
    const MeshData model = loadMesh(ds.modelPath(instances[i].obj_id).string(), 0.001f);
    ASSERT_EQ(model.colours.size(), model.vertices.size()) << "object " << instances[i].obj_id;
    for (const Rgba& c : model.colours) ASSERT_EQ(c, model.colours.front());
    const cv::Mat mask =
        cv::imread(ds.maskVisibPath(0, 0, static_cast<int>(i)).string(), cv::IMREAD_GRAYSCALE);
    if (cv::countNonZero(mask) < 100) continue;
    const cv::Scalar bgr = cv::mean(rgb, mask);
    const Eigen::Vector3f seen(bgr[2], bgr[1], bgr[0]);
    const Eigen::Vector3f painted = model.colours.front().head<3>().cast<float>();
    EXPECT_LT((chromaticity(seen) - chromaticity(painted)).cwiseAbs().sum(), 0.03f)
        << "object " << instances[i].obj_id;
  }
}

TEST(SyntheticDataset, ObjectsHideEachOtherInDefaultScenes) {
  const fs::path root = test::scratchDir("clutter");
  SyntheticDatasetParams params;
  params.scenes = 10;
  params.seed = 1;
  writeSyntheticDataset(root, params);
  const BopDataset ds(root);
  int instances = 0, occluded = 0;
  for (int scene : ds.sceneIds()) {
    const nlohmann::json gt_info =
        nlohmann::json::parse(readTextFile(ds.sceneDir(scene) / "scene_gt_info.json"));
    for (const nlohmann::json& entry : gt_info.at("0")) {
      ++instances;
      const float visible = entry.at("visib_fract").get<float>();
      EXPECT_GT(visible, 0.0f);  // every object with ground truth is in view
      occluded += visible < 0.95f;
    }
  }
  EXPECT_EQ(instances, params.scenes * params.layout.objects);
  // Objects stand apart on the table, so only some views hide one behind another: at least one
  // instance in five is partly hidden (docs/simulator.md gives the share for this seed).
  EXPECT_GE(occluded, instances / 5) << "of " << instances;
}

TEST(SyntheticDataset, SameSeedSameFilesOtherSeedOtherScenes) {
  const fs::path a = test::scratchDir("a"), b = test::scratchDir("b"), c = test::scratchDir("c");
  fs::remove(a);  // a missing folder is created
  writeSyntheticDataset(a, smallDataset(7));
  writeSyntheticDataset(b, smallDataset(7));
  writeSyntheticDataset(c, smallDataset(8));
  const std::map<std::string, std::string> fa = test::treeFiles(a), fb = test::treeFiles(b),
                                           fc = test::treeFiles(c);
  EXPECT_EQ(fa.size(), fb.size());
  for (const auto& [name, content] : fa) EXPECT_TRUE(fb.at(name) == content) << name;
  EXPECT_NE(fa.at("test/000000/depth/000000.png"), fc.at("test/000000/depth/000000.png"));
  EXPECT_NE(fa.at("test/000000/scene_gt.json"), fc.at("test/000000/scene_gt.json"));
}

TEST(SyntheticDataset, ModelsCanBeCopiedFromAFolder) {
  const fs::path from = test::scratchDir("from");
  const fs::path copied = test::scratchDir("copied");
  writeModels(from, {objectCatalogue()[0], objectCatalogue()[3]});
  SyntheticDatasetParams params = smallDataset(3);
  params.images_per_scene = 1;
  writeSyntheticDataset(copied, params, from);
  EXPECT_EQ(test::fileBytes(copied / "models" / "obj_000004.ply"),
            test::fileBytes(from / "obj_000004.ply"));
  EXPECT_FALSE(fs::exists(copied / "models" / "obj_000002.ply"));
  // Four objects from two models: instances repeat.
  const std::vector<BopGtInstance> gt = BopDataset(copied).sceneGroundTruth(0).at(0);
  ASSERT_EQ(gt.size(), 4u);
  for (const BopGtInstance& g : gt) EXPECT_TRUE(g.obj_id == 1 || g.obj_id == 4);
}

TEST(SyntheticDataset, APointModelIsRefusedByNameBeforeAnythingIsWritten) {
  const fs::path from = test::scratchDir("point_models");
  writeModels(from, {objectCatalogue()[0], objectCatalogue()[3]});
  MeshData points = loadMesh((from / "obj_000004.ply").string(), 0.001f);
  points.triangles.clear();
  writePly(from / "obj_000004.ply", points, 1000.0f);  // back to mm, vertices only
  const fs::path out = test::scratchDir("point_models_out") / "scenes";
  test::expectInputError([&] { writeSyntheticDataset(out, smallDataset(3), from); },
                         "obj_000004.ply has no faces (a point model)");
  EXPECT_FALSE(fs::exists(out));
}

TEST(SyntheticDataset, TargetsListEveryObjectAndAbsentOnesWithTheirMaps) {
  const fs::path root = test::scratchDir("synth_targets");
  SyntheticDatasetParams p = smallDataset(3);
  p.absent_per_image = 5;  // more than the 2 spare catalogue objects: both taken
  writeSyntheticDataset(root, p);
  const BopDataset ds(root);
  const std::vector<BopTarget> targets = readBopTargets(root / "test_targets_bop19.json");
  const std::map<int, std::vector<BopGtInstance>> gt = ds.sceneGroundTruth(0);
  ASSERT_EQ(targets.size(), 2u * objectCatalogue().size());
  for (const BopTarget& t : targets) {
    EXPECT_EQ(t.scene_id, 0);
    const std::vector<BopGtInstance>& instances = gt.at(t.im_id);
    const auto count = std::count_if(instances.begin(), instances.end(),
                                     [&](const BopGtInstance& g) { return g.obj_id == t.obj_id; });
    EXPECT_EQ(t.inst_count, count) << "image " << t.im_id << " object " << t.obj_id;
    // Every target has a map; an absent object's is no confident object-sized region.
    const cv::Mat probability = ds.loadProbability(0, t.im_id, t.obj_id);
    if (t.inst_count == 0) {
      EXPECT_LT(cv::countNonZero(probability > 0.7), 200) << "absent object " << t.obj_id;
    }
  }
  const fs::path none = test::scratchDir("synth_no_absent");
  p.absent_per_image = 0;
  writeSyntheticDataset(none, p);
  for (const BopTarget& t : readBopTargets(none / "test_targets_bop19.json")) {
    EXPECT_GT(t.inst_count, 0);
  }
  // The absent objects' maps are added files only: every other file is the same.
  std::map<std::string, std::string> with = test::treeFiles(root), without = test::treeFiles(none);
  for (const auto& [name, content] : without) {
    if (name == "test_targets_bop19.json") continue;
    EXPECT_EQ(with.at(name), content) << name;
  }
  p.absent_per_image = -1;
  EXPECT_THROW(writeSyntheticDataset(test::scratchDir("synth_bad_absent"), p), InputError);
}

TEST(SyntheticDataset, BadRequestsAreRefused) {
  const fs::path root = test::scratchDir("bad");
  std::ofstream(root / "keep.txt") << "user data";
  EXPECT_THROW(writeSyntheticDataset(root, smallDataset(1)), InputError);
  EXPECT_TRUE(fs::exists(root / "keep.txt"));
  SyntheticDatasetParams p = smallDataset(1);
  p.segmentation_preset = "nope";
  EXPECT_THROW(writeSyntheticDataset(root / "x", p), InputError);
  p = smallDataset(1);
  p.scenes = 0;
  EXPECT_THROW(writeSyntheticDataset(root / "y", p), InputError);
  EXPECT_THROW(writeSyntheticDataset(root / "z", smallDataset(1), root / "no_models"), InputError);
  p = smallDataset(1);
  p.catalogue = "plain";
  EXPECT_THROW(writeSyntheticDataset(root / "w", p), InputError);
}

TEST(SyntheticDataset, TexturedCatalogueShowsPrintsAndRecordsHandles) {
  const fs::path root = test::scratchDir("synth_textured");
  SyntheticDatasetParams p = smallDataset(4);
  p.catalogue = "textured";
  p.scenes = 3;
  writeSyntheticDataset(root, p);
  const BopDataset ds(root);
  ASSERT_EQ(ds.modelsInfo().size(), 3u);
  EXPECT_EQ(ds.modelsInfo().begin()->first, 7);
  EXPECT_FALSE(ds.modelsInfo().at(8).symmetric());
  int visible = 0, hidden = 0;
  for (int scene : ds.sceneIds()) {
    const std::map<int, std::vector<BopGtInstance>> gt = ds.sceneGroundTruth(scene);
    for (const auto& [im, instances] : gt) {
      // The carton in its own colours (RGB 205, 175, 125 and a blue label), not its palette
      // colour (BGR 160, 160, 60): redder than blue.
      const cv::Mat rgb = cv::imread(ds.rgbPath(scene, im).string());
      for (size_t i = 0; i < instances.size(); ++i) {
        if (instances[i].obj_id != 7) continue;
        const cv::Mat mask = cv::imread(ds.maskVisibPath(scene, im, static_cast<int>(i)).string(),
                                        cv::IMREAD_GRAYSCALE);
        const cv::Scalar mean = cv::mean(rgb, mask);
        EXPECT_GT(mean[2], mean[0]) << "scene " << scene << " image " << im;
      }
    }
    // Every printed mug instance has its handle's visibility, and only it.
    const fs::path file = ds.sceneDir(scene) / "scene_handles.json";
    const nlohmann::json handles =
        fs::exists(file) ? nlohmann::json::parse(readTextFile(file)) : nlohmann::json::object();
    for (const auto& [im, instances] : gt) {
      const long mugs = std::count_if(instances.begin(), instances.end(),
                                      [](const BopGtInstance& g) { return g.obj_id == 9; });
      const nlohmann::json entries = handles.value(std::to_string(im), nlohmann::json::array());
      ASSERT_EQ(static_cast<long>(entries.size()), mugs);
      for (const nlohmann::json& h : entries) {
        EXPECT_EQ(instances.at(h.at("gt_index").get<size_t>()).obj_id, 9);
        const long all = h.at("px_count_all"), seen = h.at("px_count_visib");
        EXPECT_GT(all, 0);
        EXPECT_LE(seen, all);
        EXPECT_EQ(h.at("handle_visible").get<bool>(), 2 * seen >= all);
        (2 * seen >= all ? visible : hidden)++;
      }
    }
  }
  EXPECT_GT(visible, 0);
  EXPECT_GT(hidden, 0);
}

}  // namespace
}  // namespace stocs
