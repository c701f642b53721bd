// ADD and ADD-S on hand-computed cases: a cross of four points (mm) under shifts and rotations.
#include <gtest/gtest.h>

#include <cmath>

#include "stocs/eval/pose_metrics.h"

namespace stocs {
namespace {

const std::vector<Eigen::Vector3f> kCross = {{10, 0, 0}, {-10, 0, 0}, {0, 20, 0}, {0, -20, 0}};

RigidPose rotZ(double deg, const Eigen::Vector3d& t = Eigen::Vector3d::Zero()) {
  return {Eigen::AngleAxisd(deg * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix(), t};
}

TEST(PoseMetrics, ShiftMovesEveryPointByItsLength) {
  const RigidPose shifted{Eigen::Matrix3d::Identity(), {3, 4, 0}};
  EXPECT_NEAR(addError(kCross, shifted, {}), 5.0, 1e-9);
  // Each shifted point is still 5 mm from its own original, and further from the others.
  EXPECT_NEAR(addsError(kCross, shifted, {}), 5.0, 1e-6);
}

TEST(PoseMetrics, HalfTurnIsASymmetryOfTheCross) {
  // 180 degrees about z swaps +-x and +-y: ADD counts 20, 20, 40, 40; ADD-S finds every point.
  EXPECT_NEAR(addError(kCross, rotZ(180), {}), 30.0, 1e-9);
  EXPECT_NEAR(addsError(kCross, rotZ(180), {}), 0.0, 1e-5);
}

TEST(PoseMetrics, QuarterTurnIsNot) {
  // (10,0,0) -> (0,10,0): 14.14 from itself, 10 from (0,20,0); (0,20,0) -> (-20,0,0): 28.28 from
  // itself, 10 from (-10,0,0).
  EXPECT_NEAR(addError(kCross, rotZ(90), {}), 15 * std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(addsError(kCross, rotZ(90), {}), 10.0, 1e-5);
}

TEST(PoseMetrics, ErrorsDoNotDependOnWhereTheTruthIs) {
  const RigidPose truth{Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix(),
                        {100, -50, 500}};
  RigidPose estimate = truth;
  estimate.t += Eigen::Vector3d(3, 4, 0);
  EXPECT_NEAR(addError(kCross, estimate, truth), 5.0, 1e-9);
  EXPECT_NEAR(addsError(kCross, estimate, truth), 5.0, 1e-4);
}

TEST(PoseMetrics, AddsMetricGivesUpAboveTheLimit) {
  const AddsMetric metric(kCross);
  EXPECT_NEAR(metric.error(rotZ(90), {}), 10.0, 1e-5);
  EXPECT_NEAR(metric.error(rotZ(90), {}, 10.5), 10.0, 1e-5);
  EXPECT_TRUE(std::isinf(metric.error(rotZ(90), {}, 9.5)));
  EXPECT_EQ(AddsMetric({}).error(rotZ(90), {}), 0.0);
}

}  // namespace
}  // namespace stocs
