// The bound behind near-duplicate hypothesis skipping: it must never report two poses as close
// when some model point moves farther than the distance.
#include <gtest/gtest.h>

#include <random>

#include "stocs/estimation/pose_proximity.h"

namespace stocs {
namespace {

ObjectModel randomModel(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-0.05f, 0.05f);
  ObjectModel model;
  for (int i = 0; i < 300; ++i) {
    model.points.emplace_back(u(rng) + 0.02f, 0.5f * u(rng), u(rng) - 0.01f);
    model.normals.emplace_back(0, 0, 1);
  }
  return model;
}

Eigen::Isometry3f perturbed(const Eigen::Isometry3f& pose, float angle, float shift,
                            std::mt19937& rng) {
  std::normal_distribution<float> n(0, 1);
  Eigen::Isometry3f out = pose;
  out.rotate(Eigen::AngleAxisf(angle, Eigen::Vector3f(n(rng), n(rng), n(rng)).normalized()));
  out.pretranslate(shift * Eigen::Vector3f(n(rng), n(rng), n(rng)).normalized());
  return out;
}

float largestMove(const ObjectModel& model, const Eigen::Isometry3f& a,
                  const Eigen::Isometry3f& b) {
  float largest = 0;
  for (const Eigen::Vector3f& m : model.points) largest = std::max(largest, (a * m - b * m).norm());
  return largest;
}

TEST(PoseProximity, WithinNeverHidesALargerMove) {
  std::mt19937 rng(3);
  const ObjectModel model = randomModel(rng);
  const PoseProximity proximity(model);
  Eigen::Isometry3f base = Eigen::Isometry3f::Identity();
  base.translation() = Eigen::Vector3f(0.1f, -0.05f, 0.7f);
  int close = 0;
  for (int k = 0; k < 2000; ++k) {
    const Eigen::Isometry3f a = perturbed(base, 0.3f * (k % 7), 0.02f * (k % 5), rng);
    // Shifts are never exactly the distance: float rounding decides such ties either way.
    const Eigen::Isometry3f b = perturbed(a, 0.002f * (k % 11), 0.00047f * (k % 13), rng);
    const float distance = 0.0025f;
    if (proximity.within(a, b, distance)) {
      ++close;
      EXPECT_LT(largestMove(model, a, b), distance) << "pair " << k;
    }
    // A centre moved by the distance or more rules the pair out (the estimator's first test).
    if ((a * proximity.centre() - b * proximity.centre()).norm() >= distance) {
      EXPECT_FALSE(proximity.within(a, b, distance)) << "pair " << k;
    }
  }
  EXPECT_GT(close, 100);  // the test exercises both outcomes
  EXPECT_LT(close, 2000);
}

TEST(PoseProximity, IdenticalPosesAreWithinAnyPositiveDistance) {
  std::mt19937 rng(5);
  const ObjectModel model = randomModel(rng);
  const PoseProximity proximity(model);
  const Eigen::Isometry3f pose = perturbed(Eigen::Isometry3f::Identity(), 1.0f, 0.5f, rng);
  EXPECT_TRUE(proximity.within(pose, pose, 1e-6f));
  EXPECT_FALSE(proximity.within(pose, pose, 0.0f));
}

}  // namespace
}  // namespace stocs
