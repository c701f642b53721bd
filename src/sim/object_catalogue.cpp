#include "stocs/sim/object_catalogue.h"

#include <Eigen/Geometry>
#include <cmath>

#include "stocs/sim/shape_meshes.h"

namespace stocs {
namespace {

constexpr int kLatheSegments = 48;
constexpr float kPi = static_cast<float>(M_PI);

/// The half-turn about `axis` (0 = x, 1 = y, 2 = z) as a BOP symmetry matrix.
Eigen::Matrix4d halfTurn(int axis) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  for (int k = 0; k < 3; ++k) m(k, k) = k == axis ? 1 : -1;
  return m;
}

/// A box with three different side lengths: the three half-turns about its axes map it onto itself.
BopObjectInfo boxSymmetries() {
  BopObjectInfo info;
  for (int axis = 0; axis < 3; ++axis) info.symmetries_discrete.push_back(halfTurn(axis));
  return info;
}

BopObjectInfo continuousAboutZ() {
  BopObjectInfo info;
  info.symmetries_continuous.push_back(ContinuousSymmetry{});
  return info;
}

/// Moves the mesh so that the origin is the centre of its bounding box (the BOP habit).
MeshData centred(MeshData mesh) {
  Eigen::Vector3f lo = mesh.vertices.front(), hi = lo;
  for (const Eigen::Vector3f& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Eigen::Vector3f centre = (lo + hi) / 2;
  for (Eigen::Vector3f& v : mesh.vertices) v -= centre;
  return mesh;
}

/// A mug 95 mm high, 80 mm across, 4 mm wall and 6 mm bottom, with a round handle whose ends are
/// buried in the wall.
MeshData mugMesh() {
  const std::vector<Eigen::Vector2f> profile_mm = {{0, 0},   {38, 0}, {40, 2}, {40, 95},
                                                   {36, 95}, {36, 8}, {34, 6}, {0, 6}};
  std::vector<Eigen::Vector2f> profile;
  for (const Eigen::Vector2f& p : profile_mm) profile.push_back(p * 0.001f);
  MeshData mug = latheMesh(profile, kLatheSegments);
  Eigen::Isometry3f at_wall = Eigen::Isometry3f::Identity();
  at_wall.translation() = Eigen::Vector3f(0.039f, 0, 0.0475f);
  appendMesh(mug, tubeArcMesh(0.028f, 0.005f, -kPi / 2, kPi / 2, 24, 12), at_wall);
  return mug;
}

/// A bowl 150 mm across and 55 mm high on a foot ring, 4 mm wall.
MeshData bowlMesh() {
  std::vector<Eigen::Vector2f> profile = {{0, 0.004f}, {0.028f, 0.004f}, {0.028f, 0}};
  constexpr int kSteps = 12;
  for (int k = 0; k <= kSteps; ++k) {  // the outside, from the foot up to the rim
    const float t = kPi / 2 * k / kSteps;
    profile.emplace_back(0.034f + 0.041f * std::sin(t), 0.055f * (1 - std::cos(t)));
  }
  for (int k = kSteps; k >= 0; --k) {  // the inside, from the rim down to the axis
    const float t = kPi / 2 * k / kSteps;
    profile.emplace_back(0.071f * std::sin(t), 0.008f + 0.047f * (1 - std::cos(t)));
  }
  return latheMesh(profile, kLatheSegments);
}

}  // namespace

MeshData asymmetricMesh() {
  MeshData mesh = boxMesh({0.1f, 0.06f, 0.04f});
  Eigen::Isometry3f on_corner = Eigen::Isometry3f::Identity();
  on_corner.translation() = Eigen::Vector3f(0.03f, 0.01f, 0.035f);
  appendMesh(mesh, boxMesh({0.04f, 0.04f, 0.03f}), on_corner);
  return mesh;
}

std::vector<CatalogueObject> objectCatalogue() {
  Eigen::Matrix4d flip = halfTurn(0);  // a cylinder upside down is the same cylinder
  BopObjectInfo cylinder = continuousAboutZ();
  cylinder.symmetries_discrete.push_back(flip);
  return {
      {1, "box", boxMesh({0.09f, 0.055f, 0.035f}), boxSymmetries()},
      {2, "long box", boxMesh({0.18f, 0.045f, 0.05f}), boxSymmetries()},
      {3, "cylinder", centred(cylinderMesh(0.033f, 0.12f, kLatheSegments)), cylinder},
      {4, "mug", centred(mugMesh()), {}},
      {5, "bowl", centred(bowlMesh()), continuousAboutZ()},
      {6, "asymmetric block", centred(asymmetricMesh()), {}},
  };
}

}  // namespace stocs
