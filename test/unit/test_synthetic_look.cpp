// The look of generated colour images (scene_look.h): the defaults draw the look synth always had,
// each variation changes the colour images and nothing of the ground truth, the same seed gives
// the same images, and look-alike distractors take the objects' colours.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "stocs/io/bop_dataset.h"
#include "stocs/sim/scene_look.h"
#include "stocs/sim/synthetic_dataset.h"
#include "test_support.h"

namespace stocs {
namespace {
namespace fs = std::filesystem;

/// One scene of two 320 x 240 views of four objects and three distractors.
SyntheticDatasetParams smallScene(uint64_t seed) {
  SyntheticDatasetParams p;
  p.images_per_scene = 2;
  p.layout.objects = 4;
  p.layout.distractors = 3;
  p.camera = {307.5, 307.5, 159.5, 119.5, 320, 240};
  p.seed = seed;
  return p;
}

std::map<std::string, std::string> generate(const std::string& name,
                                            const SyntheticDatasetParams& p) {
  const fs::path root = test::scratchDir(name);
  writeSyntheticDataset(root, p);
  return test::treeFiles(root);
}

/// Whether `file` is a colour image or a probability map (which follows the colours where the
/// simulator fires on look-alikes).
bool followsTheColours(const std::string& file) {
  return file.find("/rgb/") != std::string::npos || file.find("/prob/") != std::string::npos;
}

TEST(SyntheticLook, DefaultParamsDrawTheDefaultLook) {
  const SceneLook standard;
  const SceneLook drawn = drawSceneLook(SceneLookParams(), defaultSynthCamera(), 7);
  EXPECT_EQ(drawn.light, standard.light);
  EXPECT_EQ(drawn.ambient, standard.ambient);
  EXPECT_EQ(drawn.direct, standard.direct);
  EXPECT_EQ(drawn.light_colour, standard.light_colour);
  EXPECT_TRUE(drawn.table.empty());
  EXPECT_TRUE(drawn.background.empty());
}

TEST(SyntheticLook, EachVariationChangesTheColourImagesAndNoGroundTruth) {
  const std::map<std::string, std::string> standard = generate("standard", smallScene(3));
  const std::vector<std::pair<std::string, std::function<void(SceneLookParams&)>>> variations = {
      {"light_direction", [](SceneLookParams& l) { l.light_direction_deg = 40; }},
      {"light_intensity", [](SceneLookParams& l) { l.light_intensity = 0.5f; }},
      {"light_colour", [](SceneLookParams& l) { l.light_colour = 0.3f; }},
      {"backgrounds", [](SceneLookParams& l) { l.backgrounds = true; }},
      {"lookalike_share", [](SceneLookParams& l) { l.lookalike_share = 1; }},
      {"lookalike_jitter", [](SceneLookParams& l) { l.lookalike_jitter = 60; }}};
  for (const auto& [name, vary] : variations) {
    SyntheticDatasetParams p = smallScene(3);
    vary(p.look);
    const std::map<std::string, std::string> varied = generate(name, p);
    ASSERT_EQ(varied.size(), standard.size()) << name;
    int changed_images = 0;
    for (const auto& [file, bytes] : standard) {
      ASSERT_TRUE(varied.count(file)) << name << ": no " << file;
      if (!followsTheColours(file)) {
        EXPECT_TRUE(varied.at(file) == bytes) << name << " changed " << file;
      } else if (file.find("/rgb/") != std::string::npos) {
        changed_images += varied.at(file) != bytes;
      }
    }
    EXPECT_EQ(changed_images, 2) << name << " left colour images as they were";
  }
}

TEST(SyntheticLook, SameSeedSameImagesOtherSeedOtherLook) {
  SyntheticDatasetParams p = smallScene(4);
  p.look = {30, 0.4f, 0.2f, true, 0.8f, 30};
  EXPECT_EQ(generate("first", p), generate("again", p));

  const SceneLook a = drawSceneLook(p.look, p.camera, 1), b = drawSceneLook(p.look, p.camera, 2);
  EXPECT_NE(a.light, b.light);
  EXPECT_NE(a.light_colour, b.light_colour);
  EXPECT_NE(a.ambient, b.ambient);
  ASSERT_EQ(a.background.size(), cv::Size(320, 240));
  EXPECT_GT(cv::norm(a.table, b.table, cv::NORM_L1), 0);
  EXPECT_GT(cv::norm(a.background, b.background, cv::NORM_L1), 0);
}

/// Share of the strongly coloured pixels outside `mask` whose chromaticity (channels over their
/// sum) differs from `mask`'s mean one by more than 0.1 (sum of absolute differences; grain and
/// dark faces move a look-alike's pixels by up to about 0.06).
double shareColouredUnlike(const cv::Mat& rgb, const cv::Mat& mask) {
  const cv::Scalar mean = cv::mean(rgb, mask);
  const double sum = mean[0] + mean[1] + mean[2];
  int coloured = 0, unlike = 0;
  for (int v = 0; v < rgb.rows; ++v) {
    for (int u = 0; u < rgb.cols; ++u) {
      const cv::Vec3b c = rgb.at<cv::Vec3b>(v, u);
      const int spread = std::max({c[0], c[1], c[2]}) - std::min({c[0], c[1], c[2]});
      if (mask.at<uint8_t>(v, u) || spread < 80) continue;
      const double total = c[0] + c[1] + c[2];
      double difference = 0;
      for (int k = 0; k < 3; ++k) difference += std::abs(c[k] / total - mean[k] / sum);
      ++coloured;
      unlike += difference > 0.1;
    }
  }
  return coloured > 0 ? static_cast<double>(unlike) / coloured : 0;
}

TEST(SyntheticLook, LookalikeDistractorsTakeTheObjectsColour) {
  SyntheticDatasetParams p = smallScene(5);
  p.images_per_scene = 1;
  p.layout.objects = 1;
  p.layout.distractors = 5;
  const auto unlike = [&](float share) {
    p.look.lookalike_share = share;
    p.look.lookalike_jitter = 0;
    const fs::path root = test::scratchDir(share > 0 ? "lookalikes" : "random");
    writeSyntheticDataset(root, p);
    const BopDataset ds(root);
    return shareColouredUnlike(
        cv::imread(ds.rgbPath(0, 0).string()),
        cv::imread(ds.maskVisibPath(0, 0, 0).string(), cv::IMREAD_GRAYSCALE));
  };
  EXPECT_LT(unlike(1), 0.02);
  EXPECT_GT(unlike(0), 0.2);
}

}  // namespace
}  // namespace stocs
