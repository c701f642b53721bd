// A frame's result as messages: accepted poses with their covariance, rejected ones listed apart,
// every instance of an object, and markers (bodies, labels, uncertainty ellipsoids) that delete
// what is no longer found.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "stocs_ros/stocs_node/pose_uncertainty.h"
#include "stocs_ros/stocs_node/result_messages.h"

namespace stocs_ros {
namespace {

EstimationSetup twoObjects() {
  EstimationSetup setup;
  for (const char* name : {"box", "can"}) {
    ObjectConfig o;
    o.name = name;
    o.id = static_cast<int>(setup.config.objects.size()) + 5;
    setup.config.objects.push_back(o);
    stocs::PreparedModel m;
    for (int i = 0; i < 5000; ++i) m.model.points.emplace_back(0.001f * i, 0, 0);
    m.model.diameter = 5;
    setup.models.push_back(std::make_shared<const stocs::PreparedModel>(std::move(m)));
  }
  setup.config.objects[1].mesh_url = "package://stocs_ros/meshes/can.stl";
  setup.config.objects[1].mesh_scale = 0.001f;
  return setup;
}

ObjectOutcome outcome(size_t object, bool found, float x) {
  ObjectOutcome o{object, {}, {}};
  if (found) {
    stocs::InstancePose pose;
    pose.pose.translation() = Eigen::Vector3f(x, 0, 1);
    pose.score = 0.25f;
    o.estimate.instances.push_back(pose);
  }
  o.estimate.hypotheses = 42;
  o.estimate.seconds = 0.5;
  return o;
}

TEST(ResultMessages, OnlyFoundObjectsAreReported) {
  const EstimationSetup setup = twoObjects();
  FrameResult result;
  result.header.frame_id = "camera";
  result.header.stamp = ros::Time(12.5);
  result.objects = {outcome(0, false, 0), outcome(1, true, 0.3f)};
  const ObjectPoseArray objects = toObjectPoseArray(result, setup);
  EXPECT_EQ(objects.header.frame_id, "camera");
  EXPECT_EQ(objects.header.stamp, ros::Time(12.5));
  ASSERT_EQ(objects.objects.size(), 1u);
  EXPECT_EQ(objects.objects[0].name, "can");
  EXPECT_EQ(objects.objects[0].id, 6);
  EXPECT_FLOAT_EQ(objects.objects[0].score, 0.25f);
  EXPECT_EQ(objects.objects[0].estimation_time, 0.5);
  EXPECT_EQ(objects.objects[0].hypotheses_verified, 42);
  EXPECT_FLOAT_EQ(objects.objects[0].pose.pose.position.x, 0.3f);
  EXPECT_EQ(objects.objects[0].pose.pose.orientation.w, 1.0);
  EXPECT_TRUE(objects.rejected.empty());
  const geometry_msgs::PoseArray poses = toPoseArray(result);
  ASSERT_EQ(poses.poses.size(), 1u);
  EXPECT_EQ(poses.poses[0], objects.objects[0].pose.pose);
}

TEST(ResultMessages, MarkersShowFoundObjectsAndDeleteStaleOnes) {
  const EstimationSetup setup = twoObjects();
  std::set<MarkerKey> shown;
  FrameResult both;
  both.header.frame_id = "camera";
  both.objects = {outcome(0, true, 0.1f), outcome(1, true, 0.2f)};
  const visualization_msgs::MarkerArray first = toMarkers(both, setup, shown);
  ASSERT_EQ(first.markers.size(), 6u);
  EXPECT_EQ(first.markers[0].ns, "box");
  EXPECT_EQ(first.markers[0].type, visualization_msgs::Marker::POINTS);
  EXPECT_LE(first.markers[0].points.size(), 2000u);
  EXPECT_GT(first.markers[0].points.size(), 1000u);
  EXPECT_EQ(first.markers[1].type, visualization_msgs::Marker::TEXT_VIEW_FACING);
  EXPECT_EQ(first.markers[1].text.rfind("box ", 0), 0u) << first.markers[1].text;
  EXPECT_EQ(first.markers[2].type, visualization_msgs::Marker::MESH_RESOURCE);
  EXPECT_EQ(first.markers[2].mesh_resource, "package://stocs_ros/meshes/can.stl");
  EXPECT_FLOAT_EQ(first.markers[2].scale.x, 0.001f);
  for (const auto& m : first.markers) EXPECT_EQ(m.header.frame_id, "camera");
  EXPECT_EQ(first.markers[4].ns, "uncertainty");
  EXPECT_EQ(first.markers[4].type, visualization_msgs::Marker::SPHERE);
  EXPECT_EQ(first.markers[5].id, 1000);
  EXPECT_EQ(shown, (std::set<MarkerKey>{{"box", 0},
                                        {"box", 1},
                                        {"can", 0},
                                        {"can", 1},
                                        {"uncertainty", 0},
                                        {"uncertainty", 1000}}));

  FrameResult only_can = both;
  only_can.objects[0].estimate.instances.clear();
  const visualization_msgs::MarkerArray second = toMarkers(only_can, setup, shown);
  ASSERT_EQ(second.markers.size(), 6u);
  std::set<MarkerKey> deleted;
  for (const auto& m : second.markers) {
    if (m.action == visualization_msgs::Marker::DELETE) deleted.insert({m.ns, m.id});
  }
  EXPECT_EQ(deleted, (std::set<MarkerKey>{{"box", 0}, {"box", 1}, {"uncertainty", 0}}));
  EXPECT_EQ(shown, (std::set<MarkerKey>{{"can", 0}, {"can", 1}, {"uncertainty", 1000}}));
  // Once deleted, a marker is not deleted again.
  EXPECT_EQ(toMarkers(only_can, setup, shown).markers.size(), 3u);
}

TEST(ResultMessages, LabelsSitJustAboveTheirObjectAsTheCameraSeesIt) {
  // Two 10 cm cubes side by side, tilted, left and right of the optical axis, above and below it.
  EstimationSetup setup = twoObjects();
  for (std::shared_ptr<const stocs::PreparedModel>& shared : setup.models) {
    auto m = std::make_shared<stocs::PreparedModel>(*shared);
    shared = m;
    m->model.points.clear();
    for (int i = 0; i < 8; ++i) {
      m->model.points.emplace_back(i & 1 ? 0.05f : -0.05f, i & 2 ? 0.05f : -0.05f,
                                   i & 4 ? 0.05f : -0.05f);
    }
    m->model.diameter = 0.17f;
  }
  FrameResult result;
  result.objects = {outcome(0, true, -0.12f), outcome(1, true, 0.12f)};
  result.objects[0].estimate.best().pose.translation().y() = -0.2f;
  result.objects[1].estimate.best().pose.translation().y() = 0.15f;
  result.objects[1].estimate.best().pose.linear() =
      Eigen::AngleAxisf(0.5f, Eigen::Vector3f(1, 0.2f, 0).normalized()).matrix();
  std::set<MarkerKey> shown;
  const visualization_msgs::MarkerArray markers = toMarkers(result, setup, shown);
  ASSERT_EQ(markers.markers.size(), 6u);
  for (size_t object = 0; object < 2; ++object) {
    const visualization_msgs::Marker& label = markers.markers[2 * object + 1];
    ASSERT_EQ(label.type, visualization_msgs::Marker::TEXT_VIEW_FACING);
    const Eigen::Isometry3f& pose = result.objects[object].estimate.best().pose;
    // The object's extent in normalized image coordinates (x / z, y / z; y down).
    float left = 1e9f, right = -1e9f, top = 1e9f;
    for (const Eigen::Vector3f& p : setup.models[object]->model.points) {
      const Eigen::Vector3f q = pose * p;
      left = std::min(left, q.x() / q.z());
      right = std::max(right, q.x() / q.z());
      top = std::min(top, q.y() / q.z());
    }
    const double z = label.pose.position.z;
    const double u = label.pose.position.x / z, v = label.pose.position.y / z;
    const double half_height = label.scale.z / 2 / z;  // rviz centres the text
    EXPECT_NEAR(u, (left + right) / 2, 1e-4) << label.text;
    EXPECT_LT(v + half_height, top) << label.text << ": the text's lower edge is on the object";
    EXPECT_GT(v + half_height, top - label.scale.z / z) << label.text << ": far above the object";
    EXPECT_NEAR(z, pose.translation().z(), 0.1);
  }
}

TEST(ResultMessages, EstimateColoursAvoidTheGroundTruthsGreen) {
  EstimationSetup setup = twoObjects();
  FrameResult result;
  for (size_t k = 0; k < 40; ++k) {
    ObjectConfig o = setup.config.objects[0];
    o.name = "object_" + std::to_string(k);
    setup.config.objects.push_back(o);
    setup.models.push_back(setup.models[0]);
    result.objects.push_back(outcome(k, true, 0.01f * static_cast<float>(k)));
  }
  std::set<MarkerKey> shown;
  std::set<std::tuple<float, float, float>> distinct;
  for (const visualization_msgs::Marker& m : toMarkers(result, setup, shown).markers) {
    if (m.type == visualization_msgs::Marker::TEXT_VIEW_FACING || m.ns == "uncertainty") continue;
    // Hue in degrees of the fully saturated colour.
    const float r = m.color.r, g = m.color.g, b = m.color.b;
    const float top = std::max({r, g, b}), range = top - std::min({r, g, b});
    ASSERT_GT(range, 0.5f) << m.ns;
    const float hue = top == r   ? std::fmod(60 * (g - b) / range + 360, 360.0f)
                      : top == g ? 60 * (b - r) / range + 120
                                 : 60 * (r - g) / range + 240;
    EXPECT_TRUE(hue <= 80.5f || hue >= 179.5f) << m.ns << ": hue " << hue;
    EXPECT_EQ(m.color.a, 1.0f);
    distinct.insert({r, g, b});
  }
  EXPECT_EQ(distinct.size(), 40u);
}

/// `outcome` with `count` distinct instances at x = 0.1, 0.2, ... and falling scores.
ObjectOutcome withInstances(size_t object, int count) {
  ObjectOutcome o = outcome(object, false, 0.1f);
  for (int k = 0; k < count; ++k) {
    stocs::InstancePose p;
    p.pose.translation() = Eigen::Vector3f(0.1f * (k + 1), 0, 1);
    p.score = 0.5f - 0.1f * k;
    p.confidence = 0.9f - 0.1f * k;
    o.estimate.instances.push_back(p);
  }
  return o;
}

TEST(ResultMessages, EveryInstanceIsReportedBestFirst) {
  const EstimationSetup setup = twoObjects();
  FrameResult result;
  result.objects = {withInstances(0, 3), withInstances(1, 1)};
  const ObjectPoseArray objects = toObjectPoseArray(result, setup);
  ASSERT_EQ(objects.objects.size(), 4u);
  for (uint32_t k = 0; k < 3; ++k) {
    EXPECT_EQ(objects.objects[k].name, "box");
    EXPECT_EQ(objects.objects[k].instance, k);
    EXPECT_FLOAT_EQ(objects.objects[k].pose.pose.position.x, 0.1f * (k + 1));
    EXPECT_FLOAT_EQ(objects.objects[k].score, 0.5f - 0.1f * k);
  }
  EXPECT_EQ(objects.objects[3].name, "can");
  EXPECT_EQ(objects.objects[3].instance, 0u);
  EXPECT_EQ(toPoseArray(result).poses.size(), 4u);

  EXPECT_EQ(instanceName("box", 0), "box");
  EXPECT_EQ(instanceName("box", 2), "box_2");
  std::set<MarkerKey> shown;
  const visualization_msgs::MarkerArray markers = toMarkers(result, setup, shown);
  ASSERT_EQ(markers.markers.size(), 12u);
  EXPECT_EQ(markers.markers[4].ns, "box");
  EXPECT_EQ(markers.markers[4].id, 4);
  // The label shows the confidence (0.7), not the score (0.3).
  EXPECT_EQ(markers.markers[5].text, "box_2 0.70");

  // Fewer instances in the next frame: the markers of the lost ones are deleted.
  result.objects[0].estimate.instances.resize(1);
  const visualization_msgs::MarkerArray next = toMarkers(result, setup, shown);
  std::set<MarkerKey> deleted;
  for (const auto& m : next.markers) {
    if (m.action == visualization_msgs::Marker::DELETE) deleted.insert({m.ns, m.id});
  }
  EXPECT_EQ(
      deleted,
      (std::set<MarkerKey>{
          {"box", 2}, {"box", 3}, {"box", 4}, {"box", 5}, {"uncertainty", 1}, {"uncertainty", 2}}));
}

/// A symmetric positive-definite covariance whose entries differ but for the symmetric pairs:
/// 2^r 3^k + 2^k 3^r (x 1e-9), diagonally dominant.
stocs::PoseCovariance distinctCovariance() {
  stocs::PoseCovariance c;
  for (int r = 0; r < 6; ++r) {
    for (int k = 0; k < 6; ++k) {
      c(r, k) = 1e-9 * (std::pow(2, r) * std::pow(3, k) + std::pow(2, k) * std::pow(3, r));
    }
  }
  c.diagonal() += Eigen::Matrix<double, 6, 1>::LinSpaced(6, 1e-3, 6e-3);
  return c;
}

TEST(ResultMessages, RejectedPosesAreListedApartAndNeverPublished) {
  const EstimationSetup setup = twoObjects();
  FrameResult result;
  result.header.frame_id = "camera";
  result.objects = {withInstances(0, 2), withInstances(1, 1)};
  result.objects[0].estimate.instances[0].confidence = 0.9f;
  result.objects[0].estimate.instances[1].accepted = false;
  result.objects[0].estimate.instances[1].confidence = 0.1f;
  result.objects[0].estimate.instances[1].rejection = "confidence 0.10 below 0.50";
  result.objects[1].estimate.instances[0].accepted = false;
  result.objects[1].estimate.instances[0].confidence = 0.05f;

  const ObjectPoseArray objects = toObjectPoseArray(result, setup);
  ASSERT_EQ(objects.objects.size(), 1u);
  EXPECT_EQ(objects.objects[0].name, "box");
  EXPECT_EQ(objects.objects[0].instance, 0u);
  EXPECT_FLOAT_EQ(objects.objects[0].confidence, 0.9f);
  ASSERT_EQ(objects.rejected.size(), 2u);
  EXPECT_EQ(objects.rejected[0].name, "box");
  EXPECT_EQ(objects.rejected[0].id, 5);
  EXPECT_EQ(objects.rejected[0].instance, 1u);
  EXPECT_FLOAT_EQ(objects.rejected[0].confidence, 0.1f);
  EXPECT_EQ(objects.rejected[0].reason, "confidence 0.10 below 0.50");
  EXPECT_EQ(objects.rejected[1].name, "can");
  EXPECT_EQ(objects.rejected[1].reason, "rejected");

  EXPECT_EQ(toPoseArray(result).poses.size(), 1u);
  EXPECT_EQ(foundPoses(result).size(), 1u);
  EXPECT_EQ(rejectedPoses(result).size(), 2u);
  std::set<MarkerKey> shown;
  toMarkers(result, setup, shown);
  EXPECT_EQ(shown, (std::set<MarkerKey>{{"box", 0}, {"box", 1}, {"uncertainty", 0}}));
}

/// `setup` with every model's diameter `diameter` metres.
EstimationSetup withDiameter(EstimationSetup setup, float diameter) {
  for (std::shared_ptr<const stocs::PreparedModel>& shared : setup.models) {
    auto m = std::make_shared<stocs::PreparedModel>(*shared);
    m->model.diameter = diameter;
    shared = m;
  }
  return setup;
}

TEST(ResultMessages, TheCovarianceIsCopiedRowByRowInREP103Order) {
  // Objects smaller (10 cm) than the ellipsoid (16-30 cm across), which is then drawn to scale.
  const EstimationSetup setup = withDiameter(twoObjects(), 0.1f);
  FrameResult result;
  result.header.frame_id = "camera";
  result.header.stamp = ros::Time(3);
  result.objects = {withInstances(0, 1)};
  const stocs::PoseCovariance c = distinctCovariance();
  result.objects[0].estimate.instances[0].covariance = c;
  const ObjectPoseArray objects = toObjectPoseArray(result, setup);
  ASSERT_EQ(objects.objects.size(), 1u);
  const geometry_msgs::PoseWithCovarianceStamped single =
      toPoseWithCovariance(foundPoses(result)[0], result, setup);
  EXPECT_EQ(single.header.stamp, ros::Time(3));
  EXPECT_EQ(single.header.frame_id, "camera");
  EXPECT_EQ(single.pose, objects.objects[0].pose);
  for (int r = 0; r < 6; ++r) {
    for (int k = 0; k < 6; ++k) {
      EXPECT_EQ(objects.objects[0].pose.covariance[static_cast<size_t>(6 * r + k)], c(r, k));
    }
  }
  // The ellipsoid: diameters of the 90% region (chi-square 3 dof: 6.2514) along the eigenvectors.
  std::set<MarkerKey> shown;
  const visualization_msgs::Marker& ellipsoid = toMarkers(result, setup, shown).markers.back();
  ASSERT_EQ(ellipsoid.ns, "uncertainty");
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(c.topLeftCorner<3, 3>());
  const Eigen::Vector3d expected = 2 * (6.251388631 * eigen.eigenvalues()).cwiseSqrt();
  EXPECT_NEAR(ellipsoid.scale.x, expected.x(), 1e-6);
  EXPECT_NEAR(ellipsoid.scale.z, expected.z(), 1e-6);
  const Eigen::Quaterniond q(ellipsoid.pose.orientation.w, ellipsoid.pose.orientation.x,
                             ellipsoid.pose.orientation.y, ellipsoid.pose.orientation.z);
  EXPECT_NEAR(std::abs((q * Eigen::Vector3d::UnitZ()).dot(eigen.eigenvectors().col(2))), 1, 1e-6);
  EXPECT_FLOAT_EQ(ellipsoid.pose.position.x, 0.1f);
  EXPECT_LT(ellipsoid.color.a, 1.0f);
}

TEST(ResultMessages, AnEllipsoidSmallerThanTheObjectIsDrawnAsLargeAsTheObject) {
  const EstimationSetup setup = withDiameter(twoObjects(), 0.15f);
  FrameResult result;
  result.objects = {withInstances(0, 1)};
  // Standard deviations 1 mm and 2 mm (90% diameters 5 and 10 mm, hidden in a 15 cm object), and
  // 10 cm along the third axis (90% diameter 0.5 m, larger than the object).
  stocs::PoseCovariance c = stocs::PoseCovariance::Identity() * 1e-2;
  c(0, 0) = 1e-6;
  c(1, 1) = 4e-6;
  c(2, 2) = 1e-2;
  result.objects[0].estimate.instances[0].covariance = c;
  std::set<MarkerKey> shown;
  const visualization_msgs::Marker& ellipsoid = toMarkers(result, setup, shown).markers.back();
  ASSERT_EQ(ellipsoid.ns, "uncertainty");
  std::vector<double> diameters = {ellipsoid.scale.x, ellipsoid.scale.y, ellipsoid.scale.z};
  std::sort(diameters.begin(), diameters.end());
  EXPECT_NEAR(diameters[0], 0.15, 1e-6);
  EXPECT_NEAR(diameters[1], 0.15, 1e-6);
  EXPECT_NEAR(diameters[2], 2 * std::sqrt(6.251388631 * 1e-2), 1e-6);
}

TEST(ResultMessages, ACovarianceWithNaNIsNeverPublished) {
  const EstimationSetup setup = twoObjects();
  FrameResult result;
  result.objects = {withInstances(0, 1), withInstances(1, 1)};
  result.objects[0].estimate.instances[0].covariance = distinctCovariance();
  result.objects[0].estimate.instances[0].covariance(3, 4) = NAN;
  // The other one gives none at all (zeros): not positive definite either.
  const ObjectPoseArray objects = toObjectPoseArray(result, setup);
  ASSERT_EQ(objects.objects.size(), 2u);
  for (const ObjectPose& o : objects.objects) {
    const Eigen::Map<const Eigen::Matrix<double, 6, 6, Eigen::RowMajor>> c(
        o.pose.covariance.data());
    ASSERT_TRUE(c.allFinite()) << o.name;
    // The prior: the object's diameter (5 m here) in translation, pi in rotation.
    EXPECT_NEAR(c(3, 3), M_PI * M_PI, 1e-9) << o.name;
    EXPECT_GE(c(0, 0), 24.9) << o.name;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eigen(c);
    EXPECT_GT(eigen.eigenvalues().minCoeff(), 0) << o.name;
  }
  std::set<MarkerKey> shown;
  for (const visualization_msgs::Marker& m : toMarkers(result, setup, shown).markers) {
    EXPECT_TRUE(std::isfinite(m.scale.x) && std::isfinite(m.pose.orientation.w)) << m.ns;
  }
}

}  // namespace
}  // namespace stocs_ros
