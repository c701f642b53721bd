// The z-buffer rasteriser: depth, coverage, normals, vertex colours and occlusion against
// hand-computed values.
#include <gtest/gtest.h>

#include "stocs/geometry/surface_sampling.h"
#include "stocs/sim/depth_renderer.h"
#include "stocs/sim/shape_meshes.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

Eigen::Isometry3f at(float x, float y, float z) {
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.translation() = Eigen::Vector3f(x, y, z);
  return pose;
}

TEST(DepthRenderer, AFrontoParallelBoxFaceHasItsDepthAndProjectedArea) {
  DepthRenderer r(test::smallCamera());
  // A 10 x 10 x 2 cm box whose front face is at z = 1 m - 1 cm.
  r.draw(boxMesh({0.1f, 0.1f, 0.02f}), at(0, 0, 1.0f), 7);
  EXPECT_NEAR(r.depth().at<float>(60, 80), 0.99f, 1e-5f);
  EXPECT_EQ(r.labels().at<int>(60, 80), 7);
  const cv::Vec3f n = r.normals().at<cv::Vec3f>(60, 80);
  EXPECT_NEAR(n[2], -1.0f, 1e-5f);
  // The face spans 0.1 m * 200 px / 0.99 m = 20.2 px per side: 20 x 20 pixel centres.
  EXPECT_EQ(cv::countNonZero(r.labels() == 7), 20 * 20);
  EXPECT_EQ(r.labels().at<int>(0, 0), 0);
  EXPECT_EQ(r.depth().at<float>(0, 0), 0.0f);
}

TEST(DepthRenderer, DepthIsPerspectiveCorrectOnASlantedFace) {
  DepthRenderer r(test::smallCamera());
  Eigen::Isometry3f pose = at(0, 0, 1.0f);
  pose.linear() = Eigen::AngleAxisf(0.5f, Eigen::Vector3f::UnitY()).toRotationMatrix();
  const MeshData box = boxMesh({0.2f, 0.2f, 0.02f});
  r.draw(box, pose, 1);
  // The front face is the plane n.x = d with n = R z (facing -z after the flip) through R
  // (0,0,-0.01) + t.
  const Eigen::Vector3f n = pose.linear() * Eigen::Vector3f(0, 0, -1);
  const Eigen::Vector3f p0 = pose * Eigen::Vector3f(0, 0, -0.01f);
  for (int u : {70, 80, 90}) {
    const float z = r.depth().at<float>(60, u);
    ASSERT_GT(z, 0);
    const Eigen::Vector3f x((u - 79.5f) * z / 200, (60 - 59.5f) * z / 200, z);
    EXPECT_NEAR(n.dot(x - p0), 0.0f, 1e-5f) << "u = " << u;
  }
}

TEST(DepthRenderer, NearerObjectsHideFartherOnesInAnyOrder) {
  for (bool near_first : {true, false}) {
    DepthRenderer r(test::smallCamera());
    const MeshData box = boxMesh({0.1f, 0.1f, 0.02f});
    if (near_first) r.draw(box, at(0.02f, 0, 0.8f), 2);
    r.draw(box, at(0, 0, 1.0f), 1);
    if (!near_first) r.draw(box, at(0.02f, 0, 0.8f), 2);
    EXPECT_EQ(r.labels().at<int>(60, 80), 2);
    EXPECT_NEAR(r.depth().at<float>(60, 80), 0.79f, 1e-5f);
    EXPECT_GT(cv::countNonZero(r.labels() == 1), 0);  // the far box still shows on the left
  }
}

TEST(DepthRenderer, PointModelsSplatToTheMeshSilhouetteAndDepth) {
  const MeshData box = boxMesh({0.1f, 0.06f, 0.04f});
  Rng rng(1);
  const OrientedPoints dense = sampleMeshSurface(box, 20000, rng);  // about 1 mm apart
  const Eigen::Isometry3f pose = test::viewingPose(0.6f);           // 3 mm per pixel
  DepthRenderer mesh(test::smallCamera()), points(test::smallCamera());
  mesh.draw(box, pose, 1);
  points.drawPoints(dense.points, pose, 0.0015f, 1);
  const cv::Mat a = mesh.labels() == 1, b = points.labels() == 1;
  const double iou = static_cast<double>(cv::countNonZero(a & b)) / cv::countNonZero(a | b);
  EXPECT_GT(iou, 0.9);  // the silhouettes differ by at most a pixel along the outline
  EXPECT_GT(cv::countNonZero(a), 500);
  cv::Mat difference;
  cv::absdiff(mesh.depth(), points.depth(), difference);
  // A splat is flat at its point's depth: on faces slanted by up to 60 degrees that is off by up
  // to a pixel footprint's depth change.
  EXPECT_LT(cv::mean(difference, a & b)[0], 0.003);
}

TEST(DepthRenderer, GeometryBehindTheCameraIsSkipped) {
  DepthRenderer r(test::smallCamera());
  r.draw(boxMesh({0.1f, 0.1f, 0.1f}), at(0, 0, -1.0f), 1);
  EXPECT_EQ(cv::countNonZero(r.labels()), 0);
  CameraIntrinsics bad = test::smallCamera();
  bad.fx = 0;
  EXPECT_THROW(DepthRenderer{bad}, InputError);
}

/// `mesh` with every vertex coloured `left` where x < 0 and `right` elsewhere.
MeshData colouredByX(MeshData mesh, const VertexColour& left, const VertexColour& right) {
  for (const Eigen::Vector3f& v : mesh.vertices) mesh.colours.push_back(v.x() < 0 ? left : right);
  return mesh;
}

TEST(DepthRenderer, VertexColoursAreInterpolatedWhereTheColouredMeshShows) {
  DepthRenderer r(test::smallCamera());
  const MeshData box = boxMesh({0.1f, 0.1f, 0.02f});
  r.draw(box, at(0, 0, 1.0f), 1);
  EXPECT_TRUE(r.colours().empty());  // no colour drawn yet
  const VertexColour red(255, 0, 0, 255), blue(0, 0, 255, 255);
  r.draw(colouredByX(box, red, blue), at(0, 0, 0.8f), 2);
  ASSERT_EQ(r.colours().type(), CV_8UC4);
  // The front face at z = 0.79 m: red to blue linearly in x across its 10 cm.
  for (int u : {72, 80, 88}) {
    const float x = (u - 79.5f) * 0.79f / 200;
    const cv::Vec4b c = r.colours().at<cv::Vec4b>(60, u);
    EXPECT_NEAR(c[0], 255 * (0.05f - x) / 0.1f, 1.0f) << "u = " << u;
    EXPECT_NEAR(c[2], 255 * (x + 0.05f) / 0.1f, 1.0f) << "u = " << u;
    EXPECT_EQ(c[3], 255);
  }
  EXPECT_EQ(r.colours().at<cv::Vec4b>(0, 0), cv::Vec4b(0, 0, 0, 0));  // nothing drawn
  // A nearer box without colours hides the left half: no known colour there.
  r.draw(box, at(-0.05f, 0, 0.6f), 3);
  EXPECT_EQ(r.colours().at<cv::Vec4b>(60, 72)[3], 0);
  EXPECT_EQ(r.colours().at<cv::Vec4b>(60, 88)[3], 255);
  // Vertices of unknown colour (alpha 0) do not count: blue only, or nothing.
  DepthRenderer half(test::smallCamera());
  half.draw(colouredByX(box, VertexColour(255, 0, 0, 0), blue), at(0, 0, 0.8f), 1);
  EXPECT_EQ(half.colours().at<cv::Vec4b>(60, 72), cv::Vec4b(0, 0, 255, 255));
  DepthRenderer none(test::smallCamera());
  const VertexColour unknown(0, 0, 0, 0);
  none.draw(colouredByX(box, unknown, unknown), at(0, 0, 0.8f), 1);
  EXPECT_EQ(none.colours().at<cv::Vec4b>(60, 80)[3], 0);
  MeshData short_of_colours = box;
  short_of_colours.colours.resize(3, red);
  EXPECT_THROW(none.draw(short_of_colours, at(0, 0, 0.8f), 1), InputError);
}

}  // namespace
}  // namespace stocs
