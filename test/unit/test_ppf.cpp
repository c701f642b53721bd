// PPF feature values and their discretisation.
#include <gtest/gtest.h>

#include <set>

#include "stocs/model/ppf.h"
#include "stocs/util/random.h"

#include <Eigen/Geometry>

namespace stocs {
namespace {

constexpr float kDeg = static_cast<float>(M_PI) / 180.0f;

TEST(Ppf, FeatureOfKnownPair) {
  // Two points 0.1 m apart along x; n1 along x (angle 0 to d), n2 along y (90 deg to d and to n1).
  const PpfFeature f = computePpf({0, 0, 0}, {1, 0, 0}, {0.1f, 0, 0}, {0, 1, 0});
  EXPECT_NEAR(f.distance, 0.1f, 1e-6f);
  EXPECT_NEAR(f.angle_n1_d, 0.0f, 1e-3f);
  EXPECT_NEAR(f.angle_n2_d, 90 * kDeg, 1e-6f);
  EXPECT_NEAR(f.angle_n1_n2, 90 * kDeg, 1e-6f);
}

TEST(Ppf, SwappingThePairMirrorsTheNormalAngles) {
  const Eigen::Vector3f p1(0.01f, 0.02f, 0.5f), p2(0.07f, -0.03f, 0.55f);
  const Eigen::Vector3f n1 = Eigen::Vector3f(0.2f, 0.3f, -1).normalized();
  const Eigen::Vector3f n2 = Eigen::Vector3f(-0.4f, 0.1f, -1).normalized();
  const PpfFeature a = computePpf(p1, n1, p2, n2), b = computePpf(p2, n2, p1, n1);
  EXPECT_FLOAT_EQ(a.distance, b.distance);
  EXPECT_NEAR(a.angle_n1_d, static_cast<float>(M_PI) - b.angle_n2_d, 1e-5f);
  EXPECT_NEAR(a.angle_n2_d, static_cast<float>(M_PI) - b.angle_n1_d, 1e-5f);
  EXPECT_NEAR(a.angle_n1_n2, b.angle_n1_n2, 1e-6f);
}

TEST(Ppf, FeatureIsInvariantUnderRigidMotion) {
  const Eigen::Vector3f p1(0.01f, 0.02f, 0.5f), p2(0.07f, -0.03f, 0.55f);
  const Eigen::Vector3f n1 = Eigen::Vector3f(0.2f, 0.3f, -1).normalized();
  const Eigen::Vector3f n2 = Eigen::Vector3f(-0.4f, 0.1f, -1).normalized();
  const Eigen::Matrix3f r =
      Eigen::AngleAxisf(0.7f, Eigen::Vector3f(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3f t(0.3f, -0.2f, 1.0f);
  const PpfFeature a = computePpf(p1, n1, p2, n2);
  const PpfFeature b = computePpf(r * p1 + t, r * n1, r * p2 + t, r * n2);
  EXPECT_NEAR(a.distance, b.distance, 1e-6f);
  EXPECT_NEAR(a.angle_n1_d, b.angle_n1_d, 1e-4f);
  EXPECT_NEAR(a.angle_n2_d, b.angle_n2_d, 1e-4f);
  EXPECT_NEAR(a.angle_n1_n2, b.angle_n1_n2, 1e-4f);
}

TEST(PpfQuantizer, BinCountsFollowSteps) {
  const PpfQuantizer q(0.005f, 10 * kDeg, 0.1f);
  EXPECT_EQ(q.angleBins(), 18);
  EXPECT_EQ(q.distanceBins(), 22);  // floor(0.1 / 0.005) + 2: room for the upper neighbour
  EXPECT_EQ(q.keyCount(), 22u * 18 * 18 * 18);
}

TEST(PpfQuantizer, KeyOfOwnBinAndOutOfRange) {
  const PpfQuantizer q(0.005f, 10 * kDeg, 0.1f);
  uint32_t a = 0, b = 0;
  ASSERT_TRUE(q.key({0.0121f, 5 * kDeg, 95 * kDeg, 179 * kDeg}, a));
  ASSERT_TRUE(q.key({0.0149f, 9.9f * kDeg, 99 * kDeg, 180 * kDeg}, b));  // pi joins the last bin
  EXPECT_EQ(a, b);
  ASSERT_TRUE(q.key({0.0151f, 5 * kDeg, 95 * kDeg, 179 * kDeg}, b));
  EXPECT_NE(a, b);
  EXPECT_FALSE(q.key({0.2f, 0, 0, 0}, b));
}

TEST(PpfQuantizer, NearestBinsAreOwnAndNearerNeighbour) {
  const PpfQuantizer q(0.005f, 10 * kDeg, 0.1f);
  PpfQuantizer::Keys keys;
  // distance 0.0121 is in bin 2, nearer edge is the lower one (bin 1); angles: 12 deg -> bins 1, 0;
  // 47 deg -> bins 4, 5; 90.5 deg -> bins 9, 8.
  const int n = q.nearestKeys({0.0121f, 12 * kDeg, 47 * kDeg, 90.5f * kDeg}, keys);
  ASSERT_EQ(n, 16);
  // The own bin first, then the distance neighbour (matches are visited in this order).
  uint32_t own = 0, distance_neighbour = 0;
  ASSERT_TRUE(q.key({0.0121f, 12 * kDeg, 47 * kDeg, 90.5f * kDeg}, own));
  ASSERT_TRUE(q.key({0.0074f, 12 * kDeg, 47 * kDeg, 90.5f * kDeg}, distance_neighbour));
  EXPECT_EQ(keys[0], own);
  EXPECT_EQ(keys[1], distance_neighbour);
  std::set<uint32_t> got(keys.begin(), keys.begin() + n);
  EXPECT_EQ(got.size(), 16u);
  for (float d : {0.0121f, 0.0074f}) {
    for (float a1 : {12.f, 7.f}) {
      for (float a2 : {47.f, 52.f}) {
        for (float a3 : {90.5f, 85.f}) {
          uint32_t k;
          ASSERT_TRUE(q.key({d, a1 * kDeg, a2 * kDeg, a3 * kDeg}, k));
          EXPECT_TRUE(got.count(k)) << d << ' ' << a1 << ' ' << a2 << ' ' << a3;
        }
      }
    }
  }
}

TEST(PpfQuantizer, NearestBinsStopAtTheRangeBorders) {
  const PpfQuantizer q(0.005f, 10 * kDeg, 0.1f);
  PpfQuantizer::Keys keys;
  // Angle 2 deg: nearer edge is 0, whose neighbour (-1) does not exist; same for 179 deg at pi.
  EXPECT_EQ(q.nearestKeys({0.0121f, 2 * kDeg, 179 * kDeg, 45 * kDeg}, keys), 4);
}

TEST(PpfQuantizer, ValuesWithinHalfABinShareANearestBin) {
  const PpfQuantizer q(0.005f, 10 * kDeg, 0.1f);
  Rng rng(3);
  for (int trial = 0; trial < 2000; ++trial) {
    const PpfFeature a{0.01f + 0.08f * uniform01(rng), (10 + 160 * uniform01(rng)) * kDeg,
                       (10 + 160 * uniform01(rng)) * kDeg, (10 + 160 * uniform01(rng)) * kDeg};
    auto jitter = [&](float v, float half) { return v + (2 * uniform01(rng) - 1) * half * 0.999f; };
    const PpfFeature b{jitter(a.distance, 0.0025f), jitter(a.angle_n1_d, 5 * kDeg),
                       jitter(a.angle_n2_d, 5 * kDeg), jitter(a.angle_n1_n2, 5 * kDeg)};
    PpfQuantizer::Keys ka, kb;
    const int na = q.nearestKeys(a, ka), nb = q.nearestKeys(b, kb);
    const std::set<uint32_t> sa(ka.begin(), ka.begin() + na);
    bool shared = false;
    for (int k = 0; k < nb; ++k) shared = shared || sa.count(kb[k]);
    ASSERT_TRUE(shared) << "trial " << trial;
  }
}

}  // namespace
}  // namespace stocs
