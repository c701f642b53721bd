// The APC rotation and translation errors, the Euler convention, and symmetric objects.
#include <gtest/gtest.h>

#include <cmath>

#include "stocs/eval/rt_error.h"
#include "stocs/eval/symmetries.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

Eigen::Matrix3d rot(const Eigen::Vector3d& axis, double deg) {
  return Eigen::AngleAxisd(deg * M_PI / 180, axis.normalized()).toRotationMatrix();
}
Eigen::Matrix3d zyx(double yaw, double pitch, double roll) {
  return rot(Eigen::Vector3d::UnitZ(), yaw) * rot(Eigen::Vector3d::UnitY(), pitch) *
         rot(Eigen::Vector3d::UnitX(), roll);
}
double deg(double rad) {
  return rad * 180 / M_PI;
}

const RigidPose kTruth{zyx(40, -25, 70), {120, -30, 650}};

TEST(RtError, RollPitchYawOfTheZyxConvention) {
  const RollPitchYaw a = rollPitchYaw(zyx(30, 20, 10));
  EXPECT_NEAR(deg(a.roll), 10, 1e-9);
  EXPECT_NEAR(deg(a.pitch), 20, 1e-9);
  EXPECT_NEAR(deg(a.yaw), 30, 1e-9);
  const RollPitchYaw b = rollPitchYaw(zyx(-170, -60, 120));
  EXPECT_NEAR(deg(b.roll), 120, 1e-9);
  EXPECT_NEAR(deg(b.pitch), -60, 1e-9);
  EXPECT_NEAR(deg(b.yaw), -170, 1e-9);
}

TEST(RtError, GimbalLockPutsTheTurnIntoRoll) {
  const RollPitchYaw a = rollPitchYaw(zyx(0, 90, 40));
  EXPECT_NEAR(deg(a.pitch), 90, 1e-6);
  EXPECT_NEAR(deg(a.yaw), 0, 1e-9);
  EXPECT_NEAR(deg(a.roll), 40, 1e-6);
}

TEST(RtError, MeanOfAbsoluteAnglesOfTheErrorInTheObjectFrame) {
  EXPECT_NEAR(eulerErrorDeg(kTruth.R, kTruth.R), 0, 1e-9);
  EXPECT_NEAR(eulerErrorDeg(Eigen::Matrix3d::Identity(), zyx(30, 20, 10)), 20, 1e-9);
  // The error is R_truth^T R_estimate: a turn about the object's own x axis is pure roll.
  EXPECT_NEAR(eulerErrorDeg(kTruth.R, kTruth.R * rot(Eigen::Vector3d::UnitX(), -30)), 10, 1e-9);
  EXPECT_NEAR(eulerErrorDeg(kTruth.R, kTruth.R * zyx(-30, 20, -10)), 20, 1e-9);
}

TEST(RtError, TranslationErrorIsTheDistance) {
  RigidPose estimate = kTruth;
  estimate.t += Eigen::Vector3d(30, 0, -40);
  const RtError e = rtError(estimate, kTruth, {});
  EXPECT_NEAR(e.translation_mm, 50, 1e-9);
  EXPECT_NEAR(e.rotation_deg, 0, 1e-9);
}

TEST(RtError, DiscreteSymmetryWithAnOffsetAxis) {
  // Half turn about the z axis through (10, 0, 0): x -> Rz(180) x + (20, 0, 0).
  BopObjectInfo info;
  Eigen::Matrix4d s = Eigen::Matrix4d::Identity();
  s.topLeftCorner<3, 3>() = rot(Eigen::Vector3d::UnitZ(), 180);
  s(0, 3) = 20;
  info.symmetries_discrete.push_back(s);
  const std::vector<RigidPose> group = symmetryTransformations(info);
  ASSERT_EQ(group.size(), 2u);
  const RigidPose flipped{kTruth.R * s.topLeftCorner<3, 3>(),
                          kTruth.R * Eigen::Vector3d(20, 0, 0) + kTruth.t};
  const RtError with = rtError(flipped, kTruth, group);
  EXPECT_NEAR(with.rotation_deg, 0, 1e-9);
  EXPECT_NEAR(with.translation_mm, 0, 1e-9);
  // Without the symmetry: yaw 180 degrees, and the centre moved by 20 mm.
  const RtError without = rtError(flipped, kTruth, {});
  EXPECT_NEAR(without.rotation_deg, 60, 1e-9);
  EXPECT_NEAR(without.translation_mm, 20, 1e-9);
}

TEST(RtError, ContinuousSymmetrySampledEveryDegree) {
  BopObjectInfo info;
  info.symmetries_continuous.push_back({Eigen::Vector3d::UnitZ(), {10, 0, 0}});
  const std::vector<RigidPose> group = symmetryTransformations(info);
  ASSERT_EQ(group.size(), 360u);
  // A quarter turn about the axis through (10, 0, 0): x -> R x + (10, 0, 0) - R (10, 0, 0).
  const Eigen::Matrix3d R = rot(Eigen::Vector3d::UnitZ(), 90);
  const Eigen::Vector3d t = Eigen::Vector3d(10, 0, 0) - R * Eigen::Vector3d(10, 0, 0);
  const RtError e = rtError({kTruth.R * R, kTruth.R * t + kTruth.t}, kTruth, group);
  EXPECT_NEAR(e.rotation_deg, 0, 1e-9);
  EXPECT_NEAR(e.translation_mm, 0, 1e-9);
  // Between two samples: 37.5 degrees is 0.5 degree of yaw from the nearest, 0.5 / 3 on average.
  BopObjectInfo centred;
  centred.symmetries_continuous.push_back({Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero()});
  const RtError half = rtError({kTruth.R * rot(Eigen::Vector3d::UnitZ(), 37.5), kTruth.t}, kTruth,
                               symmetryTransformations(centred));
  EXPECT_NEAR(half.rotation_deg, 0.5 / 3, 1e-9);
}

TEST(Symmetries, GroupComposesDiscreteAndContinuous) {
  BopObjectInfo info;
  EXPECT_EQ(symmetryTransformations(info).size(), 1u);
  Eigen::Matrix4d flip = Eigen::Matrix4d::Identity();
  flip.topLeftCorner<3, 3>() = rot(Eigen::Vector3d::UnitX(), 180);
  info.symmetries_discrete.push_back(flip);
  info.symmetries_continuous.push_back({Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero()});
  const std::vector<RigidPose> group = symmetryTransformations(info, 4);
  ASSERT_EQ(group.size(), 8u);
  // Discrete transform first, then the continuous rotation: the last is Rz(270) Rx(180).
  EXPECT_TRUE(
      group.back().R.isApprox(rot(Eigen::Vector3d::UnitZ(), 270) * flip.topLeftCorner<3, 3>()));
  EXPECT_THROW(symmetryTransformations(info, 0), InputError);
  info.symmetries_continuous[0].axis = Eigen::Vector3d::Zero();
  EXPECT_THROW(symmetryTransformations(info), InputError);
}

}  // namespace
}  // namespace stocs
