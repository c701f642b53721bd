// Choosing among the poses a symmetry makes equivalent: the one nearest to the previous pose.
#include <gtest/gtest.h>

#include "stocs_ros/common/symmetric_pose.h"

namespace stocs_ros {
namespace {

Eigen::Isometry3f somePose() {
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.linear() =
      (Eigen::AngleAxisf(0.7f, Eigen::Vector3f(1, 2, 3).normalized())).toRotationMatrix();
  pose.translation() = Eigen::Vector3f(0.1f, -0.05f, 0.8f);
  return pose;
}

Eigen::Isometry3f rotationAbout(const Eigen::Vector3f& axis, float angle,
                                const Eigen::Vector3f& through) {
  Eigen::Isometry3f s = Eigen::Isometry3f::Identity();
  s.linear() = Eigen::AngleAxisf(angle, axis.normalized()).toRotationMatrix();
  s.translation() = through - s.linear() * through;
  return s;
}

TEST(SymmetricPose, ContinuousSymmetryTurnsToThePreviousPose) {
  ObjectSymmetries symmetries;
  symmetries.continuous.push_back({Eigen::Vector3f::UnitZ(), Eigen::Vector3f(0.01f, 0.02f, 0)});
  const Eigen::Isometry3f previous = somePose();
  // The same physical pose turned by 2 rad about the symmetry axis.
  const Eigen::Isometry3f estimate =
      previous * rotationAbout(Eigen::Vector3f::UnitZ(), 2.0f, symmetries.continuous[0].offset);
  const Eigen::Isometry3f chosen = nearestEquivalentPose(estimate, previous, symmetries);
  EXPECT_TRUE(chosen.matrix().isApprox(previous.matrix(), 1e-4f)) << chosen.matrix();
}

TEST(SymmetricPose, DiscreteSymmetryPicksTheNearestMember) {
  ObjectSymmetries symmetries;
  const Eigen::Isometry3f flip = rotationAbout(Eigen::Vector3f::UnitX(), static_cast<float>(M_PI),
                                               Eigen::Vector3f(0, 0, 0.02f));
  symmetries.discrete.push_back(flip);
  const Eigen::Isometry3f previous = somePose();
  const Eigen::Isometry3f flipped = previous * flip;
  EXPECT_TRUE(nearestEquivalentPose(flipped, previous, symmetries).isApprox(previous, 1e-4f));
  // Without symmetries nothing changes.
  EXPECT_TRUE(nearestEquivalentPose(flipped, previous, ObjectSymmetries{}).isApprox(flipped));
}

TEST(SymmetricPose, TrackerKeepsTheFirstPoseAndFollowsIt) {
  ObjectSymmetries symmetries;
  symmetries.continuous.push_back({Eigen::Vector3f::UnitY(), Eigen::Vector3f::Zero()});
  SymmetricPoseTracker tracker;
  const Eigen::Isometry3f first = somePose();
  EXPECT_TRUE(tracker.track(0, first, symmetries).isApprox(first));
  const Eigen::Isometry3f turned = first * rotationAbout(Eigen::Vector3f::UnitY(), 1.0f, {0, 0, 0});
  EXPECT_TRUE(tracker.track(0, turned, symmetries).isApprox(first, 1e-4f));
  // Another object has its own history; an asymmetric one is passed through.
  EXPECT_TRUE(tracker.track(1, turned, symmetries).isApprox(turned));
  EXPECT_TRUE(tracker.track(2, turned, ObjectSymmetries{}).isApprox(turned));
}

}  // namespace
}  // namespace stocs_ros
