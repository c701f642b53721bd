// The soft-segmentation simulator: determinism, range, each preset's qualitative behaviour on a
// generated scene, and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "stocs/eval/segmentation_metrics.h"
#include "stocs/sim/segmentation_simulator.h"
#include "stocs/sim/synthetic_frame.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

/// A generated tabletop frame of four catalogue objects and two distractors, some occluding others.
class SegmentationSimulatorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::vector<std::pair<int, MeshData>> models;
    for (const CatalogueObject& o : objectCatalogue()) models.emplace_back(o.id, o.mesh);
    Rng rng(5);
    SceneLayoutParams layout;
    layout.table_radius = 0.12f;  // close together: neighbours touch in the image
    const std::vector<PlacedObject> objects = arrangeObjects(models, layout, rng);
    std::vector<cv::Vec3b> colours;
    for (const PlacedObject& o : objects) {
      scene_.obj_ids.push_back(o.obj_id);
      colours.push_back(o.obj_id ? cv::Vec3b(40, 50, 200) + cv::Vec3b(0, 30 * o.obj_id, 0)
                                 : cv::Vec3b(200, 200, 60));
    }
    const SyntheticFrame frame = renderSyntheticFrame(
        objects, colours, randomCameraPose(layout, rng), defaultSynthCamera(), {}, {}, 1);
    scene_.labels = frame.labels;
    scene_.rgb = frame.rgb;
    for (int id : scene_.obj_ids) {
      if (id > 0) targets_.push_back(id);
    }
    ASSERT_GE(targets_.size(), 3u);
  }

  cv::Mat mask(int obj) const {
    cv::Mat m(scene_.labels.size(), CV_8UC1, cv::Scalar(0));
    for (size_t i = 0; i < scene_.obj_ids.size(); ++i) {
      if (scene_.obj_ids[i] == obj) m.setTo(255, scene_.labels == static_cast<int>(i) + 1);
    }
    return m;
  }

  /// Pooled over every target and seeds 1..3.
  PixelCounts counts(const SegmentationNoiseParams& params) const {
    PixelCounts c;
    for (int obj : targets_) {
      for (uint64_t seed = 1; seed <= 3; ++seed) {
        c += countSegmentPixels(simulateSegmentation(scene_, obj, params, seed), mask(obj), 0.5f);
      }
    }
    return c;
  }

  /// A catalogue object that the scene does not hold.
  int absentObject() const {
    for (const CatalogueObject& o : objectCatalogue()) {
      if (std::find(scene_.obj_ids.begin(), scene_.obj_ids.end(), o.id) == scene_.obj_ids.end()) {
        return o.id;
      }
    }
    ADD_FAILURE() << "every catalogue object is in the scene";
    return -1;
  }

  SegmentationScene scene_;
  std::vector<int> targets_;
};

TEST_F(SegmentationSimulatorTest, BlendedSeedsChangeTheMapFromFrameToFrameSmoothly) {
  const SegmentationNoiseParams noisy = segmentationPreset("noisy");
  const int obj = targets_[0];
  const cv::Mat first = simulateSegmentation(scene_, obj, noisy, 11);
  // Weight 0 is the first seed's map, exactly.
  EXPECT_EQ(cv::norm(simulateSegmentation(scene_, obj, noisy, SegmentationSeeds{11, 12, 0}), first,
                     cv::NORM_INF),
            0);
  const auto change = [&](const cv::Mat& map) { return cv::mean(cv::abs(map - first))[0]; };
  // The next frame of a sequence (keyframes 30 frames apart) differs far less from the first than
  // the next keyframe's map does, and more at each step.
  const double step =
      change(simulateSegmentation(scene_, obj, noisy, SegmentationSeeds{11, 12, 1 / 30.0f}));
  const double half =
      change(simulateSegmentation(scene_, obj, noisy, SegmentationSeeds{11, 12, 0.5f}));
  const double next = change(simulateSegmentation(scene_, obj, noisy, 12));
  EXPECT_GT(step, 0);
  EXPECT_LT(step, next / 5) << "step " << step << ", next keyframe " << next;
  EXPECT_LT(step, half);
  EXPECT_LT(half, next * 1.2);
  const SegmentationSeeds s = keyframeSeeds(5, 31, 30);
  EXPECT_EQ(s.from, keyframeSeeds(5, 30, 30).from);
  EXPECT_EQ(s.to, keyframeSeeds(5, 60, 30).from);
  EXPECT_FLOAT_EQ(s.weight, 1 / 30.0f);
}

TEST_F(SegmentationSimulatorTest, SameSeedSameMapOtherSeedOtherMap) {
  const SegmentationNoiseParams p = segmentationPreset("noisy");
  const cv::Mat a = simulateSegmentation(scene_, targets_[0], p, 7);
  const cv::Mat b = simulateSegmentation(scene_, targets_[0], p, 7);
  const cv::Mat c = simulateSegmentation(scene_, targets_[0], p, 8);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a, c, cv::NORM_L1) / a.total(), 0.005);
}

TEST_F(SegmentationSimulatorTest, EveryPresetGivesProbabilities) {
  for (const std::string& name : segmentationPresetNames()) {
    const cv::Mat p = simulateSegmentation(scene_, targets_[0], segmentationPreset(name), 3);
    ASSERT_EQ(p.type(), CV_32FC1) << name;
    ASSERT_EQ(p.size(), scene_.labels.size()) << name;
    double lo, hi;
    cv::minMaxLoc(p, &lo, &hi);
    EXPECT_GE(lo, 0.0) << name;
    EXPECT_LE(hi, 1.0) << name;
    EXPECT_GT(hi, 0.5) << name;
  }
}

TEST_F(SegmentationSimulatorTest, CleanIsTheMaskAndNoisierPresetsLoseRecallAndPrecision) {
  const std::vector<std::string> names = segmentationPresetNames();
  ASSERT_EQ(names.front(), "clean");
  std::vector<PixelCounts> c;
  for (const std::string& name : names) c.push_back(counts(segmentationPreset(name)));
  EXPECT_GT(c[0].recall(), 0.98);
  EXPECT_GT(c[0].precision(), 0.95);
  for (size_t k = 1; k < names.size(); ++k) {
    EXPECT_LT(c[k].recall(), c[k - 1].recall() - 0.02) << names[k];
    EXPECT_LT(c[k].precision(), c[k - 1].precision() - 0.02) << names[k];
  }
  EXPECT_LT(c.back().recall(), 0.8);
  EXPECT_LT(c.back().precision(), 0.8);
}

TEST_F(SegmentationSimulatorTest, MissedRegionsCoverTheRequestedShareOfTheObject) {
  SegmentationNoiseParams p;
  p.missed_fraction = 0.3f;
  // The share is drawn per map in [0.5, 1.5] x the mean, so over many maps it averages out.
  PixelCounts c;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    c += countSegmentPixels(simulateSegmentation(scene_, targets_[0], p, seed), mask(targets_[0]),
                            0.5f);
  }
  EXPECT_NEAR(1 - c.recall(), 0.3, 0.06);
  EXPECT_GT(c.precision(), 0.99);  // missing never adds pixels
}

TEST_F(SegmentationSimulatorTest, BleedingSpreadsOverTheOutlineOnly) {
  SegmentationNoiseParams p;
  p.bleed_px = 4;
  const int obj = targets_[0];
  const cv::Mat map = simulateSegmentation(scene_, obj, p, 1);
  const cv::Mat m = mask(obj);
  cv::Mat distance;
  cv::distanceTransform(m == 0, distance, cv::DIST_L2, 3);
  const cv::Mat ring = (distance > 0) & (distance <= 3);
  const cv::Mat far = distance > 20;
  EXPECT_GT(cv::mean(map, ring)[0], 0.3);
  EXPECT_EQ(cv::countNonZero((map > 0.01) & far), 0);
}

TEST_F(SegmentationSimulatorTest, NeighbourFalsePositivesFallOnOtherObjectsNotTheBackground) {
  SegmentationNoiseParams p;
  p.neighbour_fraction = 0.4f;
  PixelCounts on_objects, on_background;
  for (int obj : targets_) {
    cv::Mat other = (scene_.labels > 0) & (mask(obj) == 0);
    const cv::Mat map = simulateSegmentation(scene_, obj, p, 2);
    on_objects.false_positive += cv::countNonZero((map > 0.5) & other);
    on_background.false_positive += cv::countNonZero((map > 0.5) & (scene_.labels == 0));
  }
  EXPECT_GT(on_objects.false_positive, 200);
  EXPECT_EQ(on_background.false_positive, 0);
}

TEST_F(SegmentationSimulatorTest, LookalikesFollowColourWithRgbAndBackgroundWithout) {
  SegmentationNoiseParams p;
  p.lookalike_fraction = 0.5f;
  const int obj = targets_[0];
  const cv::Mat m = mask(obj);
  const cv::Scalar target_colour = cv::mean(scene_.rgb, m);
  cv::Mat distance(scene_.rgb.size(), CV_32F);
  for (int v = 0; v < distance.rows; ++v) {
    for (int u = 0; u < distance.cols; ++u) {
      const cv::Vec3b c = scene_.rgb.at<cv::Vec3b>(v, u);
      distance.at<float>(v, u) = static_cast<float>(
          std::hypot(c[0] - target_colour[0], c[1] - target_colour[1], c[2] - target_colour[2]));
    }
  }
  const cv::Mat fired = (simulateSegmentation(scene_, obj, p, 4) > 0.5) & (m == 0);
  ASSERT_GT(cv::countNonZero(fired), 0);
  EXPECT_LT(cv::mean(distance, fired)[0], 60);  // colours near the target's fire
  EXPECT_EQ(cv::countNonZero(fired & (distance > 120)), 0);

  SegmentationScene without_rgb = scene_;
  without_rgb.rgb = cv::Mat();
  const cv::Mat blind = (simulateSegmentation(without_rgb, obj, p, 4) > 0.5) & (m == 0);
  EXPECT_GT(cv::countNonZero(blind), 1000);
  EXPECT_EQ(cv::countNonZero(blind & (scene_.labels > 0)), 0);
}

TEST_F(SegmentationSimulatorTest, AnAbsentObjectsConfusionLiesOnAnotherObjectBelowTheRightClass) {
  SegmentationNoiseParams p = segmentationPreset("mild");
  p.absent_confusion_share = 1;
  const int absent = absentObject();
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    const cv::Mat map = simulateSegmentation(scene_, absent, p, seed);
    // The instance the map fires on: the one with the highest mean probability.
    int confused = 0;
    double confused_mean = 0;
    for (size_t i = 0; i < scene_.obj_ids.size(); ++i) {
      const cv::Mat region = scene_.labels == static_cast<int>(i) + 1;
      if (cv::countNonZero(region) == 0) continue;
      const double mean = cv::mean(map, region)[0];
      if (mean > confused_mean) {
        confused = static_cast<int>(i);
        confused_mean = mean;
      }
    }
    EXPECT_GT(confused_mean, 0.25) << "seed " << seed;
    EXPECT_LT(confused_mean, 0.8 * p.confidence) << "seed " << seed;
    // What fires lies on that instance or within the bleeding next to it.
    cv::Mat near_instance;
    cv::dilate(scene_.labels == confused + 1, near_instance, cv::Mat(), {-1, -1}, 6);
    const cv::Mat fired = map > 0.25;
    EXPECT_GT(cv::countNonZero(fired), 200) << "seed " << seed;
    EXPECT_GE(cv::countNonZero(fired & near_instance), 0.98 * cv::countNonZero(fired))
        << "seed " << seed;
  }
}

TEST_F(SegmentationSimulatorTest, AnAbsentObjectsNoiseMapHasAFewSmallBlobsAndALowMean) {
  const int absent = absentObject();
  for (const std::string& name : segmentationPresetNames()) {
    SegmentationNoiseParams p = segmentationPreset(name);
    p.absent_confusion_share = 0;
    for (uint64_t seed = 1; seed <= 4; ++seed) {
      const cv::Mat map = simulateSegmentation(scene_, absent, p, seed);
      EXPECT_LT(cv::mean(map)[0], 0.06) << name << " seed " << seed;
      if (name != "clean") continue;  // the others' noise alone can pass the blob threshold
      cv::Mat blobs, stats, centroids;
      cv::Mat fired = map > 0.15;
      const int n = cv::connectedComponentsWithStats(fired, blobs, stats, centroids) - 1;
      EXPECT_GE(n, 1) << "seed " << seed;
      EXPECT_LE(n, p.absent_blobs) << "seed " << seed;
      for (int k = 1; k <= n; ++k) {
        EXPECT_LT(stats.at<int>(k, cv::CC_STAT_AREA), p.blob_px * p.blob_px) << "seed " << seed;
      }
    }
  }
}

TEST_F(SegmentationSimulatorTest, AnAbsentObjectsMapKindIsDrawnPerSeedAndRepeatable) {
  const int absent = absentObject();
  const SegmentationNoiseParams p = segmentationPreset("noisy");
  SegmentationNoiseParams confusion = p, noise = p;
  confusion.absent_confusion_share = 1;
  noise.absent_confusion_share = 0;
  int confusions = 0, noises = 0;
  for (uint64_t seed = 1; seed <= 16; ++seed) {
    const cv::Mat map = simulateSegmentation(scene_, absent, p, seed);
    EXPECT_EQ(cv::norm(map, simulateSegmentation(scene_, absent, p, seed), cv::NORM_INF), 0.0);
    const bool is_confusion =
        cv::norm(map, simulateSegmentation(scene_, absent, confusion, seed), cv::NORM_INF) == 0;
    const bool is_noise =
        cv::norm(map, simulateSegmentation(scene_, absent, noise, seed), cv::NORM_INF) == 0;
    EXPECT_NE(is_confusion, is_noise) << "seed " << seed;
    confusions += is_confusion;
    noises += is_noise;
  }
  EXPECT_GE(confusions, 3);
  EXPECT_GE(noises, 3);
}

TEST_F(SegmentationSimulatorTest, BadInputsAreRefusedWithAClearMessage) {
  const SegmentationNoiseParams p = segmentationPreset("mild");
  SegmentationScene wrong = scene_;
  wrong.rgb = cv::Mat(10, 10, CV_8UC3);
  EXPECT_THROW(simulateSegmentation(wrong, 1, p, 0), InputError);
  wrong = scene_;
  wrong.labels.convertTo(wrong.labels, CV_16U);
  EXPECT_THROW(simulateSegmentation(wrong, 1, p, 0), InputError);
  wrong = scene_;
  wrong.obj_ids.pop_back();
  EXPECT_THROW(simulateSegmentation(wrong, 1, p, 0), InputError);
  SegmentationNoiseParams bad = p;
  bad.missed_fraction = 1.5f;
  try {
    simulateSegmentation(scene_, 1, bad, 0);
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missed_fraction 1.5 is outside [0, 1]"),
              std::string::npos)
        << e.what();
  }
  try {
    segmentationPreset("grainy");
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown segmentation preset 'grainy'; known presets: "
                                         "clean, mild, noisy, very-noisy"),
              std::string::npos)
        << e.what();
  }
}

TEST(SegmentationMetrics, CountsAgainstAHandMadeMask) {
  cv::Mat p(4, 4, CV_32FC1, cv::Scalar(0));
  cv::Mat m(4, 4, CV_8UC1, cv::Scalar(0));
  m(cv::Rect(0, 0, 2, 2)).setTo(255);  // 4 mask pixels
  p(cv::Rect(1, 0, 3, 1)).setTo(0.9);  // 3 segment pixels, 1 on the mask
  const PixelCounts c = countSegmentPixels(p, m, 0.5f);
  EXPECT_EQ(c.true_positive, 1);
  EXPECT_EQ(c.false_positive, 2);
  EXPECT_EQ(c.false_negative, 3);
  EXPECT_DOUBLE_EQ(c.precision(), 1.0 / 3);
  EXPECT_DOUBLE_EQ(c.recall(), 0.25);
  EXPECT_THROW(countSegmentPixels(p, cv::Mat(3, 4, CV_8UC1), 0.5f), InputError);
}

}  // namespace
}  // namespace stocs
