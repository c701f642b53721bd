// Base sampling (Algorithm 2): PPF consistency of all pairs, the angle and coplanarity constraints,
// the soft-segmentation prior, and instance regions.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>

#include "stocs/base_sampler.h"
#include "stocs/error.h"
#include "test_support.h"

namespace stocs {
namespace {

class BaseSamplerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    model_ = prepareModel(asymmetricMesh(), ModelSamplingParams{});
    map_ = PpfHashMap::build(model_, PpfParams{});
    // The scene is the model itself, seen at a pose: every pair is on the model.
    const Eigen::Isometry3f pose = test::viewingPose(0.6f);
    for (size_t i = 0; i < model_.size(); ++i) {
      segment_.points.push_back(pose * model_.points[i]);
      segment_.normals.push_back(pose.linear() * model_.normals[i]);
      segment_.probability.push_back(1.0f / model_.size());
      segment_.confidence.push_back(1.0f);
      segment_.pixel.push_back(static_cast<int>(i));
    }
  }

  void expectValidBase(const Base& b, const BaseSamplerParams& params) {
    const auto& p = segment_.points;
    const auto& n = segment_.normals;
    for (int x = 0; x < 4; ++x) {
      for (int y = x + 1; y < 4; ++y) {
        ASSERT_NE(b[x], b[y]);
        EXPECT_TRUE(map_.consistent(p[b[x]], n[b[x]], p[b[y]], n[b[y]])) << "pair " << x << y;
      }
    }
    const Eigen::Vector3f e12 = (p[b[1]] - p[b[0]]).normalized(),
                          e13 = (p[b[2]] - p[b[0]]).normalized();
    const float angle =
        std::acos(std::clamp(e12.dot(e13), -1.0f, 1.0f)) * 180 / static_cast<float>(M_PI);
    EXPECT_GE(angle, params.wide_angle_deg - 1e-3f);
    EXPECT_LE(angle, 180 - params.wide_angle_deg + 1e-3f);
    const Eigen::Vector3f normal = e12.cross(p[b[2]] - p[b[0]]).normalized();
    EXPECT_LE(std::abs(normal.dot(p[b[3]] - p[b[0]])), params.coplanarity + 1e-6f);
  }

  /// `count` draws with a fresh generator; failed draws are left out.
  std::vector<Base> sampleBases(const BaseSamplerParams& params, uint64_t seed, int count) const {
    const BaseSampler sampler(segment_, map_, params);
    Rng rng(seed);
    std::vector<std::pair<int, float>> scratch;
    std::vector<Base> bases;
    for (int k = 0; k < count; ++k) {
      if (const auto base = sampler.sample(rng, scratch)) bases.push_back(*base);
    }
    return bases;
  }

  ObjectModel model_;
  PpfHashMap map_;
  SoftSegment segment_;
};

TEST_F(BaseSamplerTest, BasesSatisfyEveryConstraint) {
  for (const float angle : {15.0f, 40.0f}) {
    BaseSamplerParams params;
    params.wide_angle_deg = angle;
    params.coplanarity = 0.003f;
    const std::vector<Base> bases = sampleBases(params, 5, 200);
    for (const Base& b : bases) expectValidBase(b, params);
    EXPECT_GT(bases.size(), 190u) << "angle " << angle;
  }
}

TEST_F(BaseSamplerTest, TheFirstPointFollowsTheSoftSegmentation) {
  // Points with x > 0 in the camera frame get 99 times the probability of the others.
  double total = 0;
  for (size_t i = 0; i < segment_.size(); ++i)
    total += segment_.probability[i] = segment_.points[i].x() > 0.02f ? 0.99f : 0.01f;
  for (float& p : segment_.probability) p /= static_cast<float>(total);
  const std::vector<Base> bases = sampleBases(BaseSamplerParams{}, 9, 300);
  ASSERT_GT(bases.size(), 250u);
  const auto high = std::count_if(bases.begin(), bases.end(),
                                  [&](const Base& b) { return segment_.points[b[0]].x() > 0.02f; });
  EXPECT_GT(high, 0.9 * bases.size());
}

TEST_F(BaseSamplerTest, ZeroProbabilityPointsAreNeverDrawn) {
  for (size_t i = 0; i < segment_.size(); ++i)
    segment_.probability[i] = (i % 2) ? 2.0f / segment_.size() : 0.0f;
  const std::vector<Base> bases = sampleBases(BaseSamplerParams{}, 4, 100);
  EXPECT_GT(bases.size(), 50u);
  for (const Base& b : bases) {
    for (int idx : b) EXPECT_EQ(idx % 2, 1);
  }
}

TEST_F(BaseSamplerTest, AllPointsComeFromTheRegionOfTheFirstAndNeverFromABoundary) {
  segment_.region.resize(segment_.size());
  for (size_t i = 0; i < segment_.size(); ++i) {
    const float x = segment_.points[i].x() - 0.02f;
    segment_.region[i] = std::abs(x) < 0.005f ? -1 : (x < 0 ? 1 : 2);
  }
  const std::vector<Base> bases = sampleBases(BaseSamplerParams{}, 6, 200);
  EXPECT_GT(bases.size(), 100u);
  for (const Base& b : bases) {
    const int r = segment_.region[b[0]];
    ASSERT_GE(r, 1);
    for (int idx : b) EXPECT_EQ(segment_.region[idx], r);
  }
}

TEST_F(BaseSamplerTest, NoBaseWhenNoPairIsOnTheModel) {
  SoftSegment tiny;  // four points within 2 mm: every pair is shorter than the model's minimum
  for (int i = 0; i < 4; ++i) {
    tiny.points.emplace_back(0.001f * (i & 1), 0.001f * (i >> 1), 0.5f);
    tiny.normals.emplace_back(0, 0, -1);
    tiny.probability.push_back(0.25f);
  }
  const BaseSampler sampler(tiny, map_, BaseSamplerParams{});
  Rng rng(1);
  std::vector<std::pair<int, float>> scratch;
  EXPECT_FALSE(sampler.sample(rng, scratch));
}

TEST(BaseSamplerParams, OutOfRangeValuesAreRejected) {
  BaseSamplerParams p;
  p.wide_angle_deg = 95;
  EXPECT_THROW(p.validate(), InputError);
  p = BaseSamplerParams{};
  p.coplanarity = 0;
  EXPECT_THROW(p.validate(), InputError);
  p = BaseSamplerParams{};
  p.max_attempts = 0;
  EXPECT_THROW(p.validate(), InputError);
}

}  // namespace
}  // namespace stocs
