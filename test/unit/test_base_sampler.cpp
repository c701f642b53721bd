// Base sampling (Algorithm 2): PPF consistency of all pairs, the angle and coplanarity constraints,
// the soft-segmentation prior, and instance regions.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "stocs/estimation/stages/base_sampler.h"
#include "stocs/util/error.h"
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
    BaseSamplingScratch scratch;
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

TEST_F(BaseSamplerTest, FocusedDrawsFollowAPowerOfTheSoftSegmentation) {
  // Points with x > 0.02 get twice the probability of the others: b1 falls there with chance
  // 2h / (2h + l) in a plain draw and 2^6 h / (2^6 h + l) in a focused one (h and l points on
  // either side).
  double total = 0, high_points = 0;
  for (size_t i = 0; i < segment_.size(); ++i) {
    const bool high = segment_.points[i].x() > 0.02f;
    high_points += high;
    total += segment_.probability[i] = high ? 1.0f : 0.5f;
  }
  for (float& p : segment_.probability) p /= static_cast<float>(total);
  const double low_points = static_cast<double>(segment_.size()) - high_points;
  BaseSamplerParams params;
  params.focus_exponent = 6;
  const BaseSampler sampler(segment_, map_, params);
  auto highCounts = [&](BaseWeighting weighting, int& first, int& all_four) {
    Rng rng(21);
    BaseSamplingScratch scratch;
    int drawn = 0;
    first = all_four = 0;
    for (int k = 0; k < 600; ++k) {
      const auto base = sampler.sample(rng, scratch, weighting);
      if (!base) continue;
      ++drawn;
      first += segment_.points[(*base)[0]].x() > 0.02f;
      all_four += std::all_of(base->begin(), base->end(),
                              [&](int i) { return segment_.points[i].x() > 0.02f; });
    }
    return drawn;
  };
  auto expectBinomial = [](int observed, int n, double p, const char* what) {
    const double sigma = std::sqrt(n * p * (1 - p));
    EXPECT_NEAR(observed, n * p, 4 * sigma + 1) << what;
  };
  int first_plain = 0, four_plain = 0, first_focused = 0, four_focused = 0;
  const int n_plain = highCounts(BaseWeighting::kSegment, first_plain, four_plain);
  const int n_focused = highCounts(BaseWeighting::kFocused, first_focused, four_focused);
  ASSERT_GT(n_plain, 550);
  ASSERT_GT(n_focused, 550);
  expectBinomial(first_plain, n_plain, 2 * high_points / (2 * high_points + low_points), "plain");
  expectBinomial(first_focused, n_focused, 64 * high_points / (64 * high_points + low_points),
                 "focused");
  // b2, b3 and b4 follow the same weights: whole bases on the favoured side become far more common.
  EXPECT_GT(four_focused, 2 * four_plain);

  // Exponent 1: a focused draw is the plain one.
  params.focus_exponent = 1;
  const BaseSampler unfocused(segment_, map_, params);
  Rng a(5), b(5);
  BaseSamplingScratch scratch;
  for (int k = 0; k < 20; ++k) {
    EXPECT_EQ(unfocused.sample(a, scratch, BaseWeighting::kFocused),
              sampler.sample(b, scratch, BaseWeighting::kSegment));
  }
}

TEST_F(BaseSamplerTest, TheLastPointFollowsTheSoftSegmentationAmongTheAdmissiblePoints) {
  // b4 is drawn from pi_k restricted to the points that pass every test given b1, b2 and b3. A
  // clutter of 2000 points within 1.5 mm, beside the object and within reach of b1, holds 95% of
  // pi_k, so proposals from around b1 rarely hit an admissible point and most draws of b4 come
  // from the later rounds of drawConditional. Its expected chance to fall on the object's favoured
  // side, summed over the bases, is compared with the observed count.
  const size_t object_points = segment_.size();
  double object_total = 0;
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
  for (size_t i = 0; i < object_points; ++i) {
    object_total += segment_.probability[i] = segment_.points[i].x() > 0.02f ? 0.9f : 0.1f;
    centroid += segment_.points[i] / static_cast<float>(object_points);
  }
  for (size_t i = 0; i < object_points; ++i)
    segment_.probability[i] *= static_cast<float>(0.05 / object_total);
  const Eigen::Vector3f clutter = centroid + Eigen::Vector3f(0, 0.5f * map_.maxDistance(), 0);
  Rng clutter_rng(3);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3f offset(uniform01(clutter_rng), uniform01(clutter_rng),
                                 uniform01(clutter_rng));
    segment_.points.push_back(clutter + 0.0015f * offset);
    segment_.normals.push_back((offset - Eigen::Vector3f::Constant(0.5f)).normalized());
    segment_.probability.push_back(0.95f / 2000);
    segment_.confidence.push_back(1.0f);
    segment_.pixel.push_back(static_cast<int>(segment_.pixel.size()));
  }
  BaseSamplerParams params;
  params.max_attempts = 1000;  // b1 falls on the clutter 19 times in 20 and may find no b2
  const std::vector<Base> bases = sampleBases(params, 12, 400);
  ASSERT_GT(bases.size(), 350u);
  const auto& pts = segment_.points;
  const auto& nrm = segment_.normals;
  const float cos_wide = std::cos(params.wide_angle_deg * static_cast<float>(M_PI) / 180);
  double expected = 0, variance = 0;
  int observed = 0;
  for (const Base& b : bases) {
    const Eigen::Vector3f e12 = (pts[b[1]] - pts[b[0]]).normalized();
    const Eigen::Vector3f normal = e12.cross(pts[b[2]] - pts[b[0]]).normalized();
    double favoured = 0, all = 0;
    for (int p = 0; p < static_cast<int>(segment_.size()); ++p) {
      const Eigen::Vector3f e1p = pts[p] - pts[b[0]];
      const bool admissible = p != b[1] && p != b[2] && e1p.norm() > 0 &&
                              std::abs(e12.dot(e1p) / e1p.norm()) <= cos_wide &&
                              std::abs(normal.dot(e1p)) <= params.coplanarity &&
                              map_.consistent(pts[b[0]], nrm[b[0]], pts[p], nrm[p]) &&
                              map_.consistent(pts[b[1]], nrm[b[1]], pts[p], nrm[p]) &&
                              map_.consistent(pts[b[2]], nrm[b[2]], pts[p], nrm[p]);
      if (!admissible) continue;
      all += segment_.probability[p];
      if (pts[p].x() > 0.02f) favoured += segment_.probability[p];
    }
    ASSERT_GT(all, 0) << "b4 was drawn from an empty admissible set";
    const double q = favoured / all;
    expected += q;
    variance += q * (1 - q);
    observed += pts[b[3]].x() > 0.02f;
  }
  // Four standard deviations of the sum of the Bernoulli draws.
  EXPECT_NEAR(observed, expected, 4 * std::sqrt(variance) + 1)
      << "expected " << expected << " of " << bases.size();
  // The prior must matter here, or the check above would not test it.
  EXPECT_GT(expected, 0.6 * bases.size());
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
  BaseSamplingScratch scratch;
  EXPECT_FALSE(sampler.sample(rng, scratch));
}

}  // namespace
}  // namespace stocs
