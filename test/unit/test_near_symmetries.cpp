// Near symmetries of the catalogue objects: the long box's quarter turn about its long axis (faces
// of 45 and 50 mm) is one; exact symmetries (half turns of a box, turns of a cylinder or bowl about
// its axis) and turns that move the surface (the other boxes' quarter turns) are not.
#include <gtest/gtest.h>

#include <cmath>

#include "stocs/model/near_symmetries.h"
#include "stocs/sim/object_catalogue.h"

namespace stocs {
namespace {

ObjectModel catalogueModel(const std::string& name) {
  for (const CatalogueObject& o : objectCatalogue()) {
    if (o.name == name) return prepareModel(o.mesh, ModelSamplingParams{});
  }
  ADD_FAILURE() << "no catalogue object " << name;
  return {};
}

TEST(NearSymmetries, LongBoxQuarterTurnAboutItsLongAxis) {
  const ObjectModel m = catalogueModel("long box");
  const std::vector<NearSymmetry> near = findNearSymmetries(m);
  ASSERT_EQ(near.size(), 1u);
  EXPECT_NEAR(std::abs(near[0].axis.x()), 1.0f, 0.01f);  // the box's 180 mm side is along x
  EXPECT_NEAR(near[0].angle, M_PI / 2, 1e-5);
  // The turn moves the long faces by 2.5 mm; a half turn, an exact symmetry, hardly at all.
  EXPECT_NEAR(turnedSurfaceDistance(m, Eigen::Vector3f::UnitX(), M_PI / 2), 0.0025f, 0.0005f);
  EXPECT_LT(turnedSurfaceDistance(m, Eigen::Vector3f::UnitX(), M_PI), 0.001f);
}

TEST(NearSymmetries, NoneForExactSymmetriesOrDistinctTurns) {
  for (const CatalogueObject& o : objectCatalogue()) {
    if (o.name == "long box") continue;
    EXPECT_TRUE(findNearSymmetries(prepareModel(o.mesh, ModelSamplingParams{})).empty()) << o.name;
  }
}

}  // namespace
}  // namespace stocs
