// Model preparation: even sampling and outward normals, including concave shapes.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <random>

#include "stocs/geometry/normals.h"
#include "stocs/geometry/surface_sampling.h"
#include "stocs/model/object_model.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

/// A bowl (open at the top, 4 mm wall): outer surface, rim and inner surface as one closed profile.
std::vector<Eigen::Vector2f> bowlProfile() {
  std::vector<Eigen::Vector2f> profile;
  const float outer = 0.06f, inner = 0.056f;
  for (int k = 0; k <= 12; ++k) {  // outer: bottom centre up to the rim, going up the outside
    const float a = static_cast<float>(M_PI / 2) * k / 12;
    profile.emplace_back(outer * std::sin(a), 0.06f - outer * std::cos(a));
  }
  for (int k = 12; k >= 0; --k) {  // inner: rim back down to the centre, going down the inside
    const float a = static_cast<float>(M_PI / 2) * k / 12;
    profile.emplace_back(inner * std::sin(a), 0.06f - inner * std::cos(a));
  }
  return profile;
}

TEST(ObjectModel, MeshSamplesAreEvenAndFaceOutwardOnABox) {
  const ObjectModel m = prepareModel(boxMesh({0.1f, 0.06f, 0.04f}), ModelSamplingParams{});
  EXPECT_NEAR(m.diameter, std::sqrt(0.01f + 0.0036f + 0.0016f), 1e-4f);
  EXPECT_NEAR(m.sampling_radius, 0.04f * m.diameter, 1e-6f);
  ASSERT_GT(m.size(), 200u);
  EXPECT_TRUE(m.even_sampling);
  for (size_t i = 0; i < m.size(); ++i) {
    EXPECT_NEAR(m.normals[i].norm(), 1.0f, 1e-4f);
    EXPECT_GT(m.normals[i].dot(m.points[i]), 0) << "normal " << i << " points inward";
    for (size_t j = i + 1; j < m.size(); ++j) {
      ASSERT_GE((m.points[i] - m.points[j]).norm(), m.sampling_radius * 0.999f);
    }
  }
}

TEST(ObjectModel, MeshWoundInsideOutIsFlippedAsAWhole) {
  MeshData mesh = boxMesh({0.1f, 0.06f, 0.04f});
  for (Eigen::Vector3i& t : mesh.triangles) std::swap(t[1], t[2]);
  const ObjectModel m = prepareModel(mesh, ModelSamplingParams{});
  for (size_t i = 0; i < m.size(); ++i) ASSERT_GT(m.normals[i].dot(m.points[i]), 0);
}

TEST(ObjectModel, PointModelNormalsFaceOutOfTheSolidOfAConcaveBowl) {
  // Only the vertices: a dense point model without faces, as BOP point models are.
  MeshData mesh = latheMesh(bowlProfile(), 160);
  Rng rng(1);
  const OrientedPoints dense = sampleMeshSurface(mesh, 30000, rng);
  MeshData points_only;
  points_only.vertices = dense.points;
  const ObjectModel m = prepareModel(points_only, ModelSamplingParams{});
  ASSERT_GT(m.size(), 100u);
  EXPECT_FALSE(m.even_sampling);  // a scan's density is its own
  int inner = 0, outer = 0, wrong = 0;
  const Eigen::Vector3f centre(0, 0, 0.06f);  // centre of the spherical bowl
  for (size_t i = 0; i < m.size(); ++i) {
    const float r = (m.points[i] - centre).norm();
    const Eigen::Vector3f radial = (m.points[i] - centre) / r;
    if (m.points[i].z() > 0.055f) continue;  // near the rim the normal turns; skip
    if (r < 0.058f) {  // inner surface: out of the solid means toward the cavity's centre
      ++inner;
      wrong += m.normals[i].dot(radial) > -0.5f;
    } else {  // outer surface: away from the centre
      ++outer;
      wrong += m.normals[i].dot(radial) < 0.5f;
    }
  }
  EXPECT_GT(inner, 30);
  EXPECT_GT(outer, 30);
  EXPECT_LE(wrong, (inner + outer) / 50) << "more than 2% of the normals face the wrong way";
}

TEST(ObjectModel, TheCentroidRuleWouldFailOnTheBowl) {
  // Guards the test above: flipping away from the centroid gets the inner surface wrong.
  MeshData mesh = latheMesh(bowlProfile(), 160);
  Rng rng(1);
  const OrientedPoints dense = sampleMeshSurface(mesh, 5000, rng);
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
  for (const auto& p : dense.points) centroid += p;
  centroid /= dense.points.size();
  int inner_wrong = 0, inner = 0;
  for (size_t i = 0; i < dense.points.size(); ++i) {
    const Eigen::Vector3f& p = dense.points[i];
    if (p.z() > 0.055f || (p - Eigen::Vector3f(0, 0, 0.06f)).norm() > 0.058f) continue;
    ++inner;
    const Eigen::Vector3f away = p - centroid;
    const Eigen::Vector3f n =
        dense.normals[i].dot(away) >= 0 ? dense.normals[i] : -dense.normals[i];
    inner_wrong += n.dot(dense.normals[i]) < 0;  // mesh normals are right by construction
  }
  EXPECT_GT(inner_wrong, inner / 2);
}

TEST(ObjectModel, InvalidParametersAreRejected) {
  ModelSamplingParams p;
  p.sampling_ratio = 0;
  EXPECT_THROW(prepareModel(boxMesh({0.1f, 0.1f, 0.1f}), p), InputError);
  EXPECT_THROW(prepareModel(MeshData{}, ModelSamplingParams{}), InputError);
}

TEST(Normals, MedianSpacingOfAGrid) {
  std::vector<Eigen::Vector3f> grid;
  for (int x = 0; x < 20; ++x) {
    for (int y = 0; y < 20; ++y) grid.emplace_back(0.003f * x, 0.003f * y, 0);
  }
  EXPECT_NEAR(medianSpacing(grid), 0.003f, 1e-6f);
}

// A point model that repeats its points (a face's vertices written once per face, as the fuzz
// target's box did): the spacing is that of the distinct points, and preparing it takes no more
// memory than without repeats (a spacing of 0 once asked for a 10 GB z-buffer).
TEST(Normals, RepeatedPointsKeepTheSpacingAndAPointModelPrepares) {
  std::vector<Eigen::Vector3f> grid;
  for (int x = 0; x < 20; ++x) {
    for (int y = 0; y < 20; ++y) {
      for (int copy = 0; copy < 3; ++copy) grid.emplace_back(0.003f * x, 0.003f * y, 0);
    }
  }
  EXPECT_NEAR(medianSpacing(grid), 0.003f, 1e-6f);
  EXPECT_EQ(medianSpacing(std::vector<Eigen::Vector3f>(5, Eigen::Vector3f(1, 2, 3))), 0.0f);

  MeshData box;
  for (const Eigen::Vector3f& v : boxMesh({0.06f, 0.04f, 0.03f}).vertices) {
    box.vertices.push_back(v);
    box.vertices.push_back(v);
  }
  for (int k = 0; k < 200; ++k) {  // more points on the faces, so that normals can be estimated
    const float t = static_cast<float>(k) / 200;
    box.vertices.emplace_back(0.03f, -0.02f + 0.04f * t, -0.015f + 0.03f * (k % 7) / 6.0f);
    box.vertices.emplace_back(-0.03f, -0.02f + 0.04f * t, -0.015f + 0.03f * (k % 5) / 4.0f);
  }
  ModelSamplingParams p;
  p.sampling_ratio = 0.15f;
  p.normal_neighbours = 8;
  const ObjectModel m = prepareModel(box, p);
  EXPECT_GE(m.size(), 4u);
}

// The normals' own smallest-eigenvector solver against Eigen's iterative one: with every point a
// neighbour of every other, each PCA normal is that of the whole cloud's covariance.
TEST(Normals, PcaNormalIsTheSmallestEigenvectorOfTheCovariance) {
  std::mt19937 rng(7);
  std::normal_distribution<float> gauss;
  std::uniform_real_distribution<float> uniform(0, 1);
  for (int trial = 0; trial < 60; ++trial) {
    // Spreads from a flat sheet (1e-4 of the largest) to nearly isotropic (0.9), the middle one
    // kept clear of the smallest so that the normal is well defined.
    const float smallest = std::pow(10.0f, -4.0f * uniform(rng)) * 0.9f;
    const Eigen::Vector3f spread(
        0.01f, 0.01f * (smallest + (1 - smallest) * (0.5f + uniform(rng) / 2)), 0.01f * smallest);
    const Eigen::Matrix3f rotation =
        Eigen::Quaternionf(gauss(rng), gauss(rng), gauss(rng), gauss(rng)).normalized().matrix();
    std::vector<Eigen::Vector3f> points;
    for (int i = 0; i < 100; ++i) {
      const Eigen::Vector3f g(gauss(rng), gauss(rng), gauss(rng));
      points.push_back(Eigen::Vector3f(0.3f, -0.1f, 0.8f) + rotation * spread.cwiseProduct(g));
    }
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3f& p : points) mean += p.cast<double>();
    mean /= static_cast<double>(points.size());
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (const Eigen::Vector3f& p : points) {
      covariance += (p.cast<double>() - mean) * (p.cast<double>() - mean).transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
    const Eigen::Vector3d expected = solver.eigenvectors().col(0);
    const std::vector<Eigen::Vector3f> normals = estimatePcaNormals(points, 100);
    for (size_t i = 0; i < points.size(); i += 33) {
      ASSERT_NEAR(normals[i].norm(), 1.0f, 1e-5f) << trial;
      // Within 0.1 degrees of a direction that float rounding of the points leaves uncertain.
      EXPECT_GT(std::abs(normals[i].cast<double>().dot(expected)), std::cos(0.1 * M_PI / 180))
          << "trial " << trial << " eigenvalues " << solver.eigenvalues().transpose();
    }
  }
}

TEST(Normals, CollinearPointsHaveNoPcaNormal) {
  // No plane through a line: every point falls back to the +z default.
  std::vector<Eigen::Vector3f> line;
  for (int i = 0; i < 30; ++i) line.emplace_back(0.1f + 0.002f * i, 0.2f - 0.001f * i, 0.7f);
  for (const Eigen::Vector3f& n : estimatePcaNormals(line, 8))
    EXPECT_EQ(n, Eigen::Vector3f::UnitZ());
  // A line with a hair of spread across it is still a line (second spread below 1e-3 of the
  // first in variance), a thin strip is not.
  for (const float width : {1e-5f, 1e-3f}) {
    std::vector<Eigen::Vector3f> strip = line;
    for (size_t i = 0; i < strip.size(); ++i) strip[i].z() += (i % 2 ? width : -width);
    const Eigen::Vector3f n = estimatePcaNormals(strip, 30)[15];
    if (width < 1e-4f) {
      EXPECT_EQ(n, Eigen::Vector3f::UnitZ());
    } else {
      EXPECT_NEAR(std::abs(n.dot(Eigen::Vector3f(1, 2, 0).normalized())), 1.0f, 1e-4f);
    }
  }
}

}  // namespace
}  // namespace stocs
