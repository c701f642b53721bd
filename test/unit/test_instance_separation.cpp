// Same-place test of two poses, used to suppress duplicate instances.
#include <gtest/gtest.h>

#include "stocs/estimation/instance_separation.h"
#include "stocs/model/object_model.h"
#include "test_support.h"

namespace stocs {
namespace {

TEST(InstanceSeparation, SymmetricLookAlikesAreOnePlaceNeighboursAreNot) {
  // A 10 x 6 x 4 cm box: turning it 180 degrees about z leaves the same surface.
  const ObjectModel box = prepareModel(boxMesh({0.1f, 0.06f, 0.04f}), ModelSamplingParams{});
  const InstanceSeparation separation(box, 0.1f * box.diameter);
  const Eigen::Isometry3f a = test::viewingPose(0.6f);
  Eigen::Isometry3f turned = a;
  turned.rotate(Eigen::AngleAxisf(static_cast<float>(M_PI), Eigen::Vector3f::UnitZ()));
  EXPECT_TRUE(separation.samePlace(a, turned));
  EXPECT_TRUE(separation.samePlace(turned, a));
  Eigen::Isometry3f nudged = a;
  nudged.translate(Eigen::Vector3f(0.003f, 0, 0));
  EXPECT_TRUE(separation.samePlace(a, nudged));
  // The neighbour stacked on top (4 cm along z, sharing a face) and one beside it are elsewhere.
  Eigen::Isometry3f stacked = a;
  stacked.translate(Eigen::Vector3f(0, 0, 0.04f));
  EXPECT_FALSE(separation.samePlace(a, stacked));
  EXPECT_FALSE(separation.samePlace(stacked, a));
  Eigen::Isometry3f beside = a;
  beside.translate(Eigen::Vector3f(0.1f, 0, 0));
  EXPECT_FALSE(separation.samePlace(a, beside));
}

}  // namespace
}  // namespace stocs
