// `--prob labels | masks | boxes` on a BOP dataset: the ground truth's masks and boxes, perturbed
// as a network errs, a detector's boxes file, and the errors of bad inputs.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "stocs/sim/probability_source.h"
#include "test_support.h"
#include "three_object_scene_test.h"

namespace stocs {
namespace {
namespace fs = std::filesystem;
using test::expectInputError;

class SegmentationInputSourceTest : public test::ThreeObjectSceneTest {
 protected:
  cv::Mat load(const std::string& spec, int obj, uint64_t seed = 1) const {
    return makeProbabilitySource(spec, *dataset_, seed)->load(0, 0, obj);
  }

  cv::Mat maskOf(size_t instance) const {
    return cv::imread(dataset_->maskVisibPath(0, 0, static_cast<int>(instance)).string(),
                      cv::IMREAD_GRAYSCALE) > 0;
  }

  fs::path writeBoxes(const std::string& text) const {
    const fs::path file = root_ / "boxes.json";
    std::ofstream(file) << text;
    return file;
  }
};

/// Share of the pixels of `mask` where `map` is above 0.5.
double coverage(const cv::Mat& map, const cv::Mat& mask) {
  return static_cast<double>(cv::countNonZero((map > 0.5f) & mask)) / cv::countNonZero(mask);
}

TEST_F(SegmentationInputSourceTest, MasksAndLabelsMarkEachVisibleObjectAndNothingElse) {
  const int obj = gt_[0].obj_id;
  const cv::Mat masks = load("masks", obj), labels = load("labels", obj);
  const cv::Mat mine = maskOf(0);
  EXPECT_GT(coverage(masks, mine), 0.85);
  EXPECT_LT(cv::countNonZero((masks > 0.5f) & ~mine), 0.05 * cv::countNonZero(mine));
  // Without overlapping masks, labels painted from them give the same map.
  EXPECT_LT(cv::norm(masks, labels, cv::NORM_INF), 1e-6);
  // An object the frame does not hold gets nothing.
  int absent = 1;
  while (std::any_of(gt_.begin(), gt_.end(), [&](const auto& g) { return g.obj_id == absent; }))
    ++absent;
  EXPECT_EQ(cv::countNonZero(load("masks", absent) > 0.01f), 0);
}

TEST_F(SegmentationInputSourceTest, PerturbedMasksErrLikeANetworkAndRepeatWithTheSeed) {
  const int obj = gt_[0].obj_id;
  const cv::Mat clean = load("masks", obj), perturbed = load("masks:perturbed", obj, 3);
  EXPECT_GT(cv::norm(clean, perturbed, cv::NORM_L1), 100.0);
  EXPECT_GT(coverage(perturbed, maskOf(0)), 0.6);  // mostly found
  EXPECT_EQ(cv::norm(perturbed, load("masks:perturbed", obj, 3), cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(load("labels:noisy", obj, 3), load("labels", obj), cv::NORM_L1), 100.0);
}

TEST_F(SegmentationInputSourceTest, BoxesComeFromSceneGtInfoOrTheMasksAndArePerturbed) {
  const int obj = gt_[1].obj_id;
  const cv::Mat from_info = load("boxes", obj);
  const cv::Rect box = cv::boundingRect(maskOf(1));
  EXPECT_GT(from_info.at<float>(box.y + box.height / 2, box.x + box.width / 2), 0.99f);
  EXPECT_EQ(cv::countNonZero(from_info(box)), box.area());
  EXPECT_EQ(cv::countNonZero(from_info), cv::countNonZero(load("boxes", obj)(box)));
  fs::remove(root_ / "test" / "000000" / "scene_gt_info.json");
  EXPECT_EQ(cv::norm(from_info, load("boxes", obj), cv::NORM_INF), 0.0);
  const cv::Mat perturbed = load("boxes:perturbed", obj, 5);
  EXPECT_GT(cv::norm(from_info, perturbed, cv::NORM_L1), 100.0);
  EXPECT_EQ(cv::norm(perturbed, load("boxes:perturbed", obj, 5), cv::NORM_INF), 0.0);
}

TEST_F(SegmentationInputSourceTest, ABoxesFileInBopsDetectionFormatIsRead) {
  const int obj = gt_[0].obj_id;
  const fs::path file = writeBoxes(fmt::format(
      R"([{{"scene_id": 0, "image_id": 0, "category_id": {}, "bbox": [100, 50, 40, 30],
           "score": 0.7, "time": 0.1}},
          {{"scene_id": 0, "image_id": 1, "category_id": {}, "bbox": [0, 0, 40, 30], "score": 1}}])",
      obj, obj));
  const cv::Mat map = load("boxes:" + file.string(), obj);
  EXPECT_FLOAT_EQ(map.at<float>(65, 120), 0.7f);
  EXPECT_EQ(cv::countNonZero(map), 40 * 30);
}

TEST_F(SegmentationInputSourceTest, BadInputsNameTheFileAndTheProblem) {
  const int obj = gt_[0].obj_id;
  const std::string at = writeBoxes("").string() + ": ";
  for (const auto& [text, problem] : std::vector<std::pair<std::string, std::string>>{
           {"{", "invalid JSON"},
           {"{}", "a boxes file is a list of {scene_id, image_id, category_id, bbox, score}"},
           {"[3]", "entry 0 is a JSON number, not an object"},
           {R"([{"scene_id": 0, "image_id": 0, "bbox": [0, 0, 4, 4], "score": 1}])",
            "entry 0: missing key 'category_id'"},
           {R"([{"scene_id": 0, "image_id": 0, "category_id": 1, "bbox": [0, 0, 4], "score": 1}])",
            "entry 0: 'bbox' is [0,0,4]; it must be [x, y, width, height]"},
           {R"([{"scene_id": 0, "image_id": 0, "category_id": 1, "bbox": [0, 0, -4, 4],
                 "score": 1}])",
            "entry 0: 'bbox' has width -4 and height 4; both must be positive"},
           {R"([{"scene_id": 0, "image_id": 0, "category_id": 1, "bbox": [0, 0, 4, 4],
                 "score": 2}])",
            "entry 0: 'score' is 2; it must be a number in [0, 1]"},
           {R"([{"scene_id": 0, "image_id": 0, "category_id": 99, "bbox": [0, 0, 4, 4],
                 "score": 1}])",
            "scene 0 image 0 has a box of category_id 99, which is not an object of the dataset"},
       }) {
    const fs::path file = writeBoxes(text);
    expectInputError([&] { load("boxes:" + file.string(), obj); }, at + problem);
  }
  expectInputError([&] { load("boxes:" + (root_ / "none.json").string(), obj); }, "none.json");
  expectInputError([&] { load("masks:nope", obj); }, "nope");
  expectInputError([&] { load("lines", obj); }, "unknown probability source 'lines'");

  const fs::path mask = dataset_->maskVisibPath(0, 0, 2);
  cv::imwrite(mask.string(), cv::Mat(10, 10, CV_8UC1, cv::Scalar(255)));
  expectInputError([&] { load("masks", obj); }, "mask is 10x10 but the depth image is 640x480");
  fs::remove(mask);
  expectInputError([&] { load("labels", obj); },
                   mask.string() + ": no such file (scene_gt.json has 3 instances in image 0)");
}

}  // namespace
}  // namespace stocs
