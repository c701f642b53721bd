// Results against a small hand-made BOP dataset: targets, nearest instance in a bin, symmetric
// objects, duplicates, missing estimates, and the errors for rows that do not fit the dataset.
#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "stocs/eval/dataset_evaluation.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

// Model points (mm): a cross, the same for both objects; object 2 lists its half turn about z.
const std::vector<Eigen::Vector3f> kCross = {{10, 0, 0}, {-10, 0, 0}, {0, 20, 0}, {0, -20, 0}};

Eigen::Matrix3d rotZ(double deg) {
  return Eigen::AngleAxisd(deg * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

std::string gtEntry(int obj, const Eigen::Vector3d& t) {
  return "{\"cam_R_m2c\": [1, 0, 0, 0, 1, 0, 0, 0, 1], \"cam_t_m2c\": [" + std::to_string(t.x()) +
         ", " + std::to_string(t.y()) + ", " + std::to_string(t.z()) +
         "], \"obj_id\": " + std::to_string(obj) + "}";
}

class DatasetEvaluationTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::scratchDir("eval_data");
    const auto scene = root_ / "test" / "000000";
    std::filesystem::create_directories(scene / "prob");
    std::filesystem::create_directories(root_ / "models");
    for (const char* obj : {"obj_000001.ply", "obj_000002.ply"}) {
      writePly(root_ / "models" / obj, MeshData{kCross, {}, {}});
    }
    std::ofstream(root_ / "models" / "models_info.json")
        << R"({"1": {"diameter": 40}, "2": {"diameter": 40, "symmetries_discrete": )"
        << R"([[-1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]]}})";
    // Image 0: a bin of two instances of object 1 and one of object 2; image 1: object 1 alone.
    std::ofstream(scene / "scene_gt.json")
        << "{\"0\": [" << gtEntry(1, {0, 0, 500}) << ", " << gtEntry(2, {0, 100, 500}) << ", "
        << gtEntry(1, {200, 0, 500}) << "], \"1\": [" << gtEntry(1, {0, 0, 600}) << "]}";
    cv::imwrite((scene / "prob" / "000000_000001.png").string(),
                cv::Mat(4, 4, CV_16UC1, cv::Scalar(5000)));
  }

  BopResult row(int im, int obj, const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                double score = 1) const {
    BopResult r;
    r.im_id = im;
    r.obj_id = obj;
    r.R = R;
    r.t_mm = t;
    r.score = score;
    return r;
  }

  std::string errorOf(const std::vector<BopResult>& results) {
    const BopDataset ds(root_);
    DatasetEvaluator evaluator(ds);
    try {
      evaluator.evaluate(listTargets(ds, {}, {}), results, "r.csv");
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  std::filesystem::path root_;
};

TEST_F(DatasetEvaluationTest, TargetsAreObjectsPerImage) {
  const BopDataset ds(root_);
  const std::vector<Target> all = listTargets(ds, {}, {});
  ASSERT_EQ(all.size(), 3u);  // object 1 once in image 0 despite two instances
  EXPECT_EQ(all[0], (Target{0, 0, 1}));
  EXPECT_EQ(all[1], (Target{0, 0, 2}));
  EXPECT_EQ(all[2], (Target{0, 1, 1}));
  EXPECT_EQ(listTargets(ds, {0}, {2}).size(), 1u);
  const auto real = makeProbabilitySource("real", ds, 0);
  const std::vector<Target> with_maps = listTargets(ds, {}, {}, real.get());
  ASSERT_EQ(with_maps.size(), 1u);
  EXPECT_EQ(with_maps[0], (Target{0, 0, 1}));
  EXPECT_THROW(listTargets(ds, {4}, {}), InputError);
}

TEST_F(DatasetEvaluationTest, NearestInstanceSymmetryDuplicatesAndMissing) {
  const BopDataset ds(root_);
  DatasetEvaluator evaluator(ds);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const ResultsEvaluation ev = evaluator.evaluate(
      listTargets(ds, {}, {}),
      {
          row(0, 1, I, {203, 4, 500}, 0.9),     // 5 mm from the second instance of object 1
          row(0, 1, I, {0, 0, 500}, 0.2),       // lower score for the same target: ignored
          row(0, 2, rotZ(180), {0, 100, 500}),  // object 2 turned by its symmetry
          row(1, 2, I, {0, 0, 600}),            // object 2 is not in image 1
      },
      "r.csv");
  EXPECT_EQ(ev.duplicates, 1);
  EXPECT_EQ(ev.not_targets, 1);
  ASSERT_EQ(ev.targets.size(), 3u);

  const TargetResult& bin = ev.targets[0];
  EXPECT_EQ(bin.target, (Target{0, 0, 1}));
  EXPECT_DOUBLE_EQ(bin.score, 0.9);
  EXPECT_EQ(bin.gt_index, 2);
  EXPECT_NEAR(bin.errors.add_mm, 5, 1e-4);  // model points pass through float
  EXPECT_NEAR(bin.errors.adds_mm, 5, 1e-5);
  EXPECT_NEAR(bin.errors.translation_mm, 5, 1e-9);
  EXPECT_NEAR(bin.errors.rotation_deg, 0, 1e-9);
  EXPECT_DOUBLE_EQ(bin.errors.diameter_mm, 40);
  EXPECT_FALSE(bin.errors.addsSuccess());  // 5 mm is not below 10% of 40 mm
  EXPECT_TRUE(bin.errors.rtSuccess());

  const TargetResult& sym = ev.targets[1];
  EXPECT_EQ(sym.gt_index, 1);
  EXPECT_TRUE(sym.errors.symmetric);
  EXPECT_NEAR(sym.errors.add_mm, 30, 1e-4);  // points moved by 20, 20, 40, 40
  EXPECT_NEAR(sym.errors.adds_mm, 0, 1e-5);
  EXPECT_NEAR(sym.errors.addOrAddsMm(), 0, 1e-5);
  EXPECT_NEAR(sym.errors.rotation_deg, 0, 1e-9);  // the listed symmetry
  EXPECT_TRUE(sym.errors.addOrAddsSuccess());

  const TargetResult& missing = ev.targets[2];
  EXPECT_FALSE(missing.errors.found);
  EXPECT_EQ(missing.gt_index, -1);
  EXPECT_TRUE(std::isinf(missing.errors.adds_mm));
  EXPECT_TRUE(std::isinf(missing.errors.rotation_deg));
  EXPECT_FALSE(missing.errors.rtSuccess());
}

TEST_F(DatasetEvaluationTest, RowsThatDoNotFitTheDatasetAreNamed) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  EXPECT_NE(errorOf({row(0, 7, I, {0, 0, 500})})
                .find("r.csv: row scene 0 image 0 object 7: "
                      "unknown object 7"),
            std::string::npos);
  EXPECT_NE(errorOf({row(9, 1, I, {0, 0, 500})}).find("scene 0 image 9 has no ground truth"),
            std::string::npos);
  BopResult other_scene = row(0, 1, I, {0, 0, 500});
  other_scene.scene_id = 5;
  EXPECT_NE(errorOf({other_scene}).find("scene 5 is not in dataset"), std::string::npos);
}

}  // namespace
}  // namespace stocs
