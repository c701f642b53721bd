// Tabletop arrangements: stable resting poses, objects on the plane and apart, cameras in range.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "stocs/sim/scene_layout.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

std::vector<std::pair<int, MeshData>> catalogueModels() {
  std::vector<std::pair<int, MeshData>> models;
  for (const CatalogueObject& o : objectCatalogue()) models.emplace_back(o.id, o.mesh);
  return models;
}

/// The model axis that a resting rotation puts straight down.
Eigen::Vector3f downAxis(const Eigen::Matrix3f& rest) {
  return rest.transpose() * Eigen::Vector3f(0, 0, -1);
}

bool restsOn(const std::vector<Eigen::Matrix3f>& rests, const Eigen::Vector3f& model_axis) {
  return std::any_of(rests.begin(), rests.end(), [&](const Eigen::Matrix3f& r) {
    return downAxis(r).isApprox(model_axis, 1e-5f);
  });
}

TEST(SceneLayout, BoxesRestOnAnyFaceMugsUprightOrOnTheirRimNeverOnTheHandle) {
  EXPECT_EQ(restingOrientations(boxMesh({0.1f, 0.06f, 0.04f})).size(), 6u);
  const std::vector<CatalogueObject> objects = objectCatalogue();
  const std::vector<Eigen::Matrix3f> mug = restingOrientations(objects[3].mesh);
  EXPECT_TRUE(restsOn(mug, -Eigen::Vector3f::UnitZ()));  // upright
  EXPECT_TRUE(restsOn(mug, Eigen::Vector3f::UnitZ()));   // on its rim
  EXPECT_FALSE(restsOn(mug, Eigen::Vector3f::UnitX()));  // the handle is at +x
  const std::vector<Eigen::Matrix3f> bowl = restingOrientations(objects[4].mesh);
  EXPECT_TRUE(restsOn(bowl, -Eigen::Vector3f::UnitZ()));
  EXPECT_FALSE(restsOn(bowl, Eigen::Vector3f::UnitY()));  // not on its side
}

TEST(SceneLayout, CentreOfMassOfSolids) {
  EXPECT_LT(centreOfMass(boxMesh({0.1f, 0.06f, 0.04f})).norm(), 1e-6f);
  // Asymmetric block: box (240 cm^3 at the origin) and block (48 cm^3 at (3, 1, 3.5) cm).
  const Eigen::Vector3f expected = Eigen::Vector3f(0.03f, 0.01f, 0.035f) * 48 / 288;
  EXPECT_LT((centreOfMass(asymmetricMesh()) - expected).norm(), 1e-6f);
}

TEST(SceneLayout, ObjectsRestOnThePlaneWithoutOverlapping) {
  SceneLayoutParams params;
  params.objects = 6;
  params.distractors = 3;
  params.table_radius = 0.3f;  // room for all nine
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    Rng rng(seed);
    const std::vector<PlacedObject> placed = arrangeObjects(catalogueModels(), params, rng);
    ASSERT_EQ(placed.size(), 9u) << "seed " << seed;
    std::vector<std::vector<cv::Point2f>> hulls;
    for (const PlacedObject& o : placed) {
      float lowest = 1e9f;
      std::vector<cv::Point2f> xy;
      for (const Eigen::Vector3f& v : o.mesh.vertices) {
        const Eigen::Vector3f p = o.pose * v;
        lowest = std::min(lowest, p.z());
        xy.emplace_back(p.x(), p.y());
      }
      EXPECT_NEAR(lowest, 0.0f, 1e-5f);
      std::vector<cv::Point2f> hull;
      cv::convexHull(xy, hull);
      hulls.push_back(hull);
    }
    // No vertex of one object lies under another one's footprint.
    for (size_t a = 0; a < placed.size(); ++a) {
      for (size_t b = 0; b < placed.size(); ++b) {
        if (a == b) continue;
        for (const cv::Point2f& p : hulls[a]) {
          ASSERT_LT(cv::pointPolygonTest(hulls[b], p, true), 0) << "seed " << seed;
        }
      }
    }
    int distractors = 0;
    for (const PlacedObject& o : placed) distractors += o.obj_id == 0;
    EXPECT_EQ(distractors, 3);
  }
}

TEST(SceneLayout, CamerasLookAtTheTableFromTheRequestedRange) {
  SceneLayoutParams params;
  Rng rng(3);
  for (int k = 0; k < 20; ++k) {
    const Eigen::Isometry3f pose = randomCameraPose(params, rng);
    const Eigen::Vector3f centre = pose * Eigen::Vector3f(0, 0, 0.03f);
    EXPECT_LT(std::hypot(centre.x(), centre.y()) / centre.z(), 0.1f);  // near the optical axis
    const Eigen::Vector3f eye = pose.inverse().translation();
    const float distance = eye.norm();
    EXPECT_GE(distance, params.min_distance - 0.05f);
    EXPECT_LE(distance, params.max_distance + 0.05f);
    const float elevation =
        std::asin((eye.z() - 0.03f) / (eye - Eigen::Vector3f(0, 0, 0.03f)).norm());
    EXPECT_GE(elevation * 180 / M_PI, params.min_elevation_deg - 5);
    EXPECT_LE(elevation * 180 / M_PI, params.max_elevation_deg + 5);
    // Image "down" points down towards the table: the camera's y axis has a negative world z.
    EXPECT_LT((pose.linear().transpose() * Eigen::Vector3f::UnitY()).z(), 0);
  }
}

TEST(SceneLayout, SameSeedSameArrangementAndBadParametersAreRefused) {
  SceneLayoutParams params;
  Rng a(9), b(9);
  const std::vector<PlacedObject> first = arrangeObjects(catalogueModels(), params, a);
  const std::vector<PlacedObject> second = arrangeObjects(catalogueModels(), params, b);
  ASSERT_EQ(first.size(), second.size());
  for (size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(first[i].obj_id, second[i].obj_id);
    EXPECT_TRUE(first[i].pose.isApprox(second[i].pose));
  }
  params.max_distance = 0.1f;
  EXPECT_THROW(arrangeObjects(catalogueModels(), params, a), InputError);
}

}  // namespace
}  // namespace stocs
