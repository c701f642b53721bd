// ADD, ADD-S and MSSD on hand-computed cases: a cross of four points (mm) under shifts and
// rotations, and a box turned over with and without its declared symmetries.
#include <gtest/gtest.h>

#include <cmath>

#include "stocs/eval/object_metrics.h"
#include "stocs/eval/pose_metrics.h"
#include "stocs/sim/shape_meshes.h"

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

TEST(PoseMetrics, MssdIsTheLargestDistanceForTheBestSymmetry) {
  const std::vector<RigidPose> none = {RigidPose{}}, half_turn = {RigidPose{}, rotZ(180)};
  EXPECT_NEAR(mssdError(kCross, {Eigen::Matrix3d::Identity(), {3, 4, 0}}, {}, none), 5.0, 1e-9);
  // A half-turn moves (0, 20) to (0, -20): 40 mm, unless the half-turn is a symmetry.
  EXPECT_NEAR(mssdError(kCross, rotZ(180), {}, none), 40.0, 1e-9);
  EXPECT_NEAR(mssdError(kCross, rotZ(180), {}, half_turn), 0.0, 1e-9);
  // A quarter turn is 90 degrees from both symmetric poses: (0, 20) moves 20 sqrt(2) either way.
  EXPECT_NEAR(mssdError(kCross, rotZ(90), {}, half_turn), 20 * std::sqrt(2.0), 1e-9);
  // The symmetry applies in the model frame, before the truth's pose.
  const RigidPose truth = rotZ(30, {10, 20, 500});
  const RigidPose turned{truth.R * rotZ(180).R, truth.t};
  EXPECT_NEAR(mssdError(kCross, turned, truth, half_turn), 0.0, 1e-9);
  EXPECT_TRUE(std::isinf(mssdError(kCross, turned, truth, {})));
  EXPECT_EQ(mssdError({}, turned, truth, none), 0.0);
}

TEST(ObjectMetrics, ABoxTurnedOverPassesMssdOnlyWithItsSymmetry) {
  std::vector<Eigen::Vector3f> corners_mm;
  for (const Eigen::Vector3f& v : boxMesh({90, 55, 35}).vertices) corners_mm.push_back(v);
  BopObjectInfo symmetric;
  Eigen::Matrix4d flip = Eigen::Matrix4d::Identity();  // the half-turn about x
  flip(1, 1) = flip(2, 2) = -1;
  symmetric.symmetries_discrete.push_back(flip);
  const RigidPose truth = rotZ(40, {0, 0, 600});
  const RigidPose turned{truth.R * flip.topLeftCorner<3, 3>(), truth.t};
  const TargetErrors with = ObjectMetrics(corners_mm, symmetric).evaluate(&turned, {truth});
  EXPECT_NEAR(with.mssd_mm, 0.0, 1e-6);
  EXPECT_TRUE(with.mssdSuccess());
  EXPECT_DOUBLE_EQ(with.mssdRecall(), 1.0);
  const TargetErrors without = ObjectMetrics(corners_mm, {}).evaluate(&turned, {truth});
  // Every corner moves to the opposite one across the x axis: sqrt(55^2 + 35^2).
  EXPECT_NEAR(without.mssd_mm, std::hypot(55.0, 35.0), 1e-6);
  EXPECT_FALSE(without.mssdSuccess());
  EXPECT_DOUBLE_EQ(without.mssdRecall(), 0.0);  // 65 mm is above half the 111 mm diameter
  // Shifted 30 mm: 0.27 of the diameter, below 5 of the 10 thresholds (0.3, ..., 0.5).
  const RigidPose shifted{truth.R, truth.t + Eigen::Vector3d(30, 0, 0)};
  EXPECT_DOUBLE_EQ(ObjectMetrics(corners_mm, {}).evaluate(&shifted, {truth}).mssdRecall(), 0.5);
  EXPECT_TRUE(std::isinf(ObjectMetrics(corners_mm, {}).evaluate(nullptr, {truth}).mssd_mm));
}

}  // namespace
}  // namespace stocs
