// Choosing among the poses a declared symmetry makes equivalent: the one nearest to a previous
// pose, else the canonical one.
#include <gtest/gtest.h>

#include "stocs/model/object_symmetries.h"

namespace stocs {
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

TEST(ObjectSymmetries, ContinuousSymmetryTurnsToThePreviousPose) {
  ObjectSymmetries symmetries;
  symmetries.continuous.push_back({Eigen::Vector3f::UnitZ(), Eigen::Vector3f(0.01f, 0.02f, 0)});
  const Eigen::Isometry3f previous = somePose();
  // The same physical pose turned by 2 rad about the symmetry axis.
  const Eigen::Isometry3f estimate =
      previous * rotationAbout(Eigen::Vector3f::UnitZ(), 2.0f, symmetries.continuous[0].offset);
  const Eigen::Isometry3f chosen = nearestEquivalentPose(estimate, previous, symmetries);
  EXPECT_TRUE(chosen.matrix().isApprox(previous.matrix(), 1e-4f)) << chosen.matrix();
}

TEST(ObjectSymmetries, DiscreteSymmetryPicksTheNearestMember) {
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

TEST(ObjectSymmetries, CanonicalPoseIsTheSameForEveryEquivalent) {
  ObjectSymmetries symmetries;
  symmetries.discrete.push_back(
      rotationAbout(Eigen::Vector3f::UnitX(), static_cast<float>(M_PI), Eigen::Vector3f::Zero()));
  symmetries.continuous.push_back({Eigen::Vector3f::UnitZ(), Eigen::Vector3f::Zero()});
  const Eigen::Isometry3f pose = somePose();
  const Eigen::Isometry3f canonical = canonicalPose(pose, symmetries);
  for (const float angle : {0.5f, 2.0f, -2.5f}) {
    for (const Eigen::Isometry3f& flip : {Eigen::Isometry3f::Identity(), symmetries.discrete[0]}) {
      const Eigen::Isometry3f equivalent =
          pose * flip * rotationAbout(Eigen::Vector3f::UnitZ(), angle, Eigen::Vector3f::Zero());
      EXPECT_TRUE(canonicalPose(equivalent, symmetries).isApprox(canonical, 1e-4f))
          << angle << "\n"
          << canonicalPose(equivalent, symmetries).matrix();
    }
  }
  // The canonical pose is an equivalent, not another pose: the same place, a symmetric rotation.
  EXPECT_TRUE(canonical.translation().isApprox(pose.translation(), 1e-5f));
  EXPECT_TRUE(canonicalPose(pose, ObjectSymmetries{}).isApprox(pose));
}

TEST(ObjectSymmetries, IsSymmetryKnowsTheDeclaredMotions) {
  ObjectSymmetries symmetries;
  symmetries.continuous.push_back({Eigen::Vector3f::UnitZ(), Eigen::Vector3f(0.01f, 0, 0)});
  const Eigen::Vector3f centre(0.01f, 0, 0.02f);
  const Eigen::Isometry3f about_axis =
      rotationAbout(Eigen::Vector3f::UnitZ(), 1.2f, symmetries.continuous[0].offset);
  EXPECT_TRUE(isSymmetry(about_axis, symmetries, centre, 0.01f, 0.001f));
  const Eigen::Isometry3f about_x = rotationAbout(Eigen::Vector3f::UnitX(), 1.2f, centre);
  EXPECT_FALSE(isSymmetry(about_x, symmetries, centre, 0.01f, 0.001f));
  EXPECT_FALSE(isSymmetry(about_axis, ObjectSymmetries{}, centre, 0.01f, 0.001f));
}

}  // namespace
}  // namespace stocs
