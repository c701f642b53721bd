// Probability sources: real maps, the simulator on visible ground-truth masks (from mask_visib or
// rendered from mesh and point models), and the real maps of ../shared/datasets against those
// masks.
#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "stocs/eval/segmentation_metrics.h"
#include "stocs/geometry/surface_sampling.h"
#include "stocs/io/mesh_io.h"
#include "stocs/sim/ground_truth_masks.h"
#include "stocs/sim/probability_source.h"
#include "stocs/util/error.h"
#include "test_support.h"
#include "three_object_scene_test.h"

namespace stocs {
namespace {
namespace fs = std::filesystem;

class ProbabilitySourceTest : public test::ThreeObjectSceneTest {
 protected:
  /// The visible mask of every instance of `obj`, from mask_visib.
  cv::Mat mask(int obj) const {
    cv::Mat m(480, 640, CV_8UC1, cv::Scalar(0));
    for (size_t i = 0; i < gt_.size(); ++i) {
      if (gt_[i].obj_id != obj) continue;
      m |= cv::imread(dataset_->maskVisibPath(0, 0, static_cast<int>(i)).string(),
                      cv::IMREAD_GRAYSCALE);
    }
    return m;
  }
};

TEST_F(ProbabilitySourceTest, SimUsesRealMapsWhereTheyExistAndSimulatesElsewhere) {
  const int kept = gt_[0].obj_id, removed = gt_[1].obj_id;
  fs::remove(dataset_->probabilityPath(0, 0, removed));
  const auto real = makeProbabilitySource("real", *dataset_, 1);
  const auto sim = makeProbabilitySource("sim:clean", *dataset_, 1);
  const auto simonly = makeProbabilitySource("simonly:clean", *dataset_, 1);
  EXPECT_EQ(sim->spec(), "sim:clean");
  EXPECT_TRUE(real->namesObjects() && sim->namesObjects());  // a network's maps, real or simulated
  EXPECT_TRUE(real->available(0, 0, kept));
  EXPECT_FALSE(real->available(0, 0, removed));
  EXPECT_TRUE(sim->available(0, 0, removed));
  EXPECT_TRUE(simonly->available(0, 0, kept));
  EXPECT_FALSE(sim->available(0, 0, 99));  // no model in the dataset
  // A model the frame's ground truth does not hold gets the simulator's absent-object map.
  int absent = 0;
  for (const auto& [id, info] : dataset_->modelsInfo()) {
    if (std::none_of(gt_.begin(), gt_.end(),
                     [&](const BopGtInstance& g) { return g.obj_id == id; }))
      absent = id;
  }
  ASSERT_GT(absent, 0);
  EXPECT_TRUE(simonly->available(0, 0, absent));
  EXPECT_LT(cv::mean(simonly->load(0, 0, absent))[0], 0.2);

  const cv::Mat file = dataset_->loadProbability(0, 0, kept);
  EXPECT_EQ(cv::norm(sim->load(0, 0, kept), file, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(simonly->load(0, 0, kept), file, cv::NORM_INF), 0.0);
  for (int obj : {kept, removed}) {
    const PixelCounts c = countSegmentPixels(simonly->load(0, 0, obj), mask(obj), 0.5f);
    EXPECT_GT(c.recall(), 0.97) << obj;
    EXPECT_GT(c.precision(), 0.9) << obj;
  }
  EXPECT_EQ(cv::norm(sim->load(0, 0, removed), simonly->load(0, 0, removed), cv::NORM_INF), 0.0);
}

TEST_F(ProbabilitySourceTest, SimulatedMapsDependOnTheSeedOnly) {
  const int obj = gt_[2].obj_id;
  const auto a = makeProbabilitySource("simonly:noisy", *dataset_, 5);
  const auto b = makeProbabilitySource("simonly:noisy", *dataset_, 5);
  const auto c = makeProbabilitySource("simonly:noisy", *dataset_, 6);
  b->load(0, 0, gt_[0].obj_id);  // asking for another object first changes nothing
  EXPECT_EQ(cv::norm(a->load(0, 0, obj), b->load(0, 0, obj), cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a->load(0, 0, obj), c->load(0, 0, obj), cv::NORM_INF), 0.0);
}

TEST_F(ProbabilitySourceTest, GeometricMapsComeFromTheDepthAloneForEveryModel) {
  std::filesystem::remove_all(root_ / "test" / "000000" / "prob");  // no map to lean on
  const auto geometric = makeProbabilitySource("geometric", *dataset_, 0);
  EXPECT_EQ(geometric->spec(), "geometric");
  EXPECT_FALSE(geometric->namesObjects());  // every region of an object's size
  EXPECT_TRUE(geometric->available(0, 0, gt_[0].obj_id));
  EXPECT_FALSE(geometric->available(0, 0, 99));  // no model in the dataset
  cv::Mat anywhere(480, 640, CV_8UC1, cv::Scalar(0));
  int covered = 0;
  for (const BopGtInstance& g : gt_) {
    const cv::Mat map = geometric->load(0, 0, g.obj_id);
    ASSERT_EQ(map.type(), CV_32FC1);
    ASSERT_EQ(map.size(), anywhere.size());
    covered += cv::mean(map, mask(g.obj_id))[0] > 0.2;
    anywhere |= mask(g.obj_id);
  }
  EXPECT_GE(covered, 2);  // an object hidden behind another may fit no region
  // The table is no candidate: far from the objects every map is 0.
  cv::Mat near;
  cv::dilate(anywhere, near, cv::Mat(), cv::Point(-1, -1), 20);
  const cv::Mat far = ~near & (dataset_->loadDepth(0, 0) > 0);
  EXPECT_LT(cv::mean(geometric->load(0, 0, gt_[0].obj_id), far)[0], 0.05);
}

TEST_F(ProbabilitySourceTest, TheWholeSceneIsEveryModelsMap) {
  const auto whole = makeProbabilitySource("whole", *dataset_, 0);
  EXPECT_EQ(whole->spec(), "whole");
  EXPECT_FALSE(whole->namesObjects());
  EXPECT_TRUE(whole->available(0, 0, gt_[0].obj_id));
  EXPECT_FALSE(whole->available(0, 0, 99));  // no model in the dataset
  const cv::Mat map = whole->load(0, 0, gt_[0].obj_id);
  EXPECT_EQ(map.size(), cv::Size(640, 480));
  EXPECT_EQ(map.type(), CV_32FC1);
  double lowest = 0;
  cv::minMaxLoc(map, &lowest);
  EXPECT_EQ(lowest, 1.0);
}

TEST_F(ProbabilitySourceTest, UnknownSourcesAndPresetsAreRefusedWithTheKnownOnes) {
  try {
    makeProbabilitySource("network", *dataset_, 0);
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("unknown probability source 'network'"), std::string::npos) << m;
    EXPECT_NE(m.find("'sim:PRESET'"), std::string::npos) << m;
  }
  EXPECT_THROW(makeProbabilitySource("sim:grainy", *dataset_, 0), InputError);
  EXPECT_THROW(makeProbabilitySource("simonly:", *dataset_, 0), InputError);
}

TEST_F(ProbabilitySourceTest, RenderedMasksMatchMaskVisibForMeshAndPointModels) {
  const GroundTruthMasks masks(*dataset_);
  EXPECT_TRUE(masks.hasMaskVisib(0, 0, gt_.size()));
  const SegmentationScene from_files = masks.frame(0, 0);
  fs::remove_all(dataset_->sceneDir(0) / "mask_visib");
  EXPECT_FALSE(masks.hasMaskVisib(0, 0, gt_.size()));
  const SegmentationScene from_meshes = masks.frame(0, 0);
  ASSERT_EQ(from_meshes.obj_ids, from_files.obj_ids);
  EXPECT_EQ(from_meshes.rgb.size(), from_files.labels.size());

  // The same models as dense points only, as BOP point models are.
  for (const BopGtInstance& g : gt_) {
    const MeshData mesh = loadMesh(dataset_->modelPath(g.obj_id).string(), 0.001f);
    Rng rng(1);
    MeshData points;
    points.vertices = sampleMeshSurface(mesh, 30000, rng).points;
    writePly(dataset_->modelPath(g.obj_id), points, 1000.0f);
  }
  const SegmentationScene from_points = GroundTruthMasks(*dataset_).frame(0, 0);
  for (size_t i = 0; i < gt_.size(); ++i) {
    const int label = static_cast<int>(i) + 1;
    const cv::Mat visible = from_files.labels == label;
    // The generated scene has a distractor that the ground truth does not know: rendered masks
    // may show more of an object than is visible, never less.
    const cv::Mat meshes = from_meshes.labels == label, points_only = from_points.labels == label;
    EXPECT_GT(cv::countNonZero(visible & meshes), 0.99 * cv::countNonZero(visible)) << i;
    const double iou = static_cast<double>(cv::countNonZero(meshes & points_only)) /
                       cv::countNonZero(meshes | points_only);
    EXPECT_GT(iou, 0.9) << i;
  }
}

TEST(ProbabilitySourceRealData, RealNetworkMapsAgreeWithRenderedAndStoredMasks) {
  STOCS_REQUIRE_DATASETS(root);
  // The packed dove: point models rendered as splats. Real map: 96.9% precision, 93.2% recall.
  const BopDataset packed(root / "rutgers-packed");
  const GroundTruthMasks packed_masks(packed);
  EXPECT_FALSE(packed_masks.hasMaskVisib(0, 0, 16));
  const SegmentationScene frame = packed_masks.frame(0, 0);
  cv::Mat dove(frame.labels.size(), CV_8UC1, cv::Scalar(0));
  for (size_t i = 0; i < frame.obj_ids.size(); ++i) {
    if (frame.obj_ids[i] == 1) dove.setTo(255, frame.labels == static_cast<int>(i) + 1);
  }
  const PixelCounts c = countSegmentPixels(packed.loadProbability(0, 0, 1), dove, 0.5f);
  EXPECT_GT(c.precision(), 0.93);
  EXPECT_GT(c.recall(), 0.9);

  // YCB-Video frames carry mask_visib; the mild preset keeps most of every object.
  const BopDataset ycbv(root / "ycbv-0000");
  EXPECT_TRUE(GroundTruthMasks(ycbv).hasMaskVisib(0, 1, 3));
  const auto sim = makeProbabilitySource("sim:mild", ycbv, 1);
  const SegmentationScene ycb = GroundTruthMasks(ycbv).frame(0, 1);
  for (size_t i = 0; i < ycb.obj_ids.size(); ++i) {
    ASSERT_TRUE(sim->available(0, 1, ycb.obj_ids[i]));
    const cv::Mat m = ycb.labels == static_cast<int>(i) + 1;
    EXPECT_GT(countSegmentPixels(sim->load(0, 1, ycb.obj_ids[i]), m, 0.5f).recall(), 0.8);
  }
}

}  // namespace
}  // namespace stocs
