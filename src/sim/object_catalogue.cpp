#include "stocs/sim/object_catalogue.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/Geometry>
#include <cmath>

#include "stocs/sim/shape_meshes.h"
#include "stocs/util/error.h"

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

/// A closed cylinder: any turn about its axis, and upside down the same cylinder.
BopObjectInfo cylinderSymmetries() {
  BopObjectInfo info = continuousAboutZ();
  info.symmetries_discrete.push_back(halfTurn(0));
  return info;
}

/// The centre of the mesh's bounding box.
Eigen::Vector3f boxCentre(const MeshData& mesh) {
  Eigen::Vector3f lo = mesh.vertices.front(), hi = lo;
  for (const Eigen::Vector3f& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return (lo + hi) / 2;
}

/// The mesh moved by `offset`.
MeshData shifted(MeshData mesh, const Eigen::Vector3f& offset) {
  for (Eigen::Vector3f& v : mesh.vertices) v += offset;
  return mesh;
}

/// Moves the mesh so that the origin is the centre of its bounding box (the BOP habit).
MeshData centred(MeshData mesh) {
  const Eigen::Vector3f centre = boxCentre(mesh);
  return shifted(std::move(mesh), -centre);
}

/// The mug's round handle, its ends buried in the wall at +x.
MeshData mugHandle() {
  Eigen::Isometry3f at_wall = Eigen::Isometry3f::Identity();
  at_wall.translation() = Eigen::Vector3f(0.039f, 0, 0.0475f);
  MeshData handle;
  appendMesh(handle, tubeArcMesh(0.028f, 0.005f, -kPi / 2, kPi / 2, 24, 12), at_wall);
  return handle;
}

/// A mug 95 mm high, 80 mm across, 4 mm wall and 6 mm bottom, with a round handle whose ends are
/// buried in the wall; `segments` around and the outside wall in `wall_rings` bands.
MeshData mugMesh(int segments = kLatheSegments, int wall_rings = 1) {
  std::vector<Eigen::Vector2f> profile_mm = {{0, 0}, {38, 0}, {40, 2}};
  for (int k = 1; k < wall_rings; ++k) profile_mm.emplace_back(40, 2 + 93.0f * k / wall_rings);
  profile_mm.insert(profile_mm.end(), {{40, 95}, {36, 95}, {36, 8}, {34, 6}, {0, 6}});
  std::vector<Eigen::Vector2f> profile;
  for (const Eigen::Vector2f& p : profile_mm) profile.push_back(p * 0.001f);
  MeshData mug = latheMesh(profile, segments);
  appendMesh(mug, mugHandle());
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

constexpr int kPrintSegments = 96;  // around a printed lathe: the print's sides step by 3.75 deg

VertexColour rgb(uint8_t r, uint8_t g, uint8_t b) {
  return VertexColour(r, g, b, 255);
}

/// 72 x 68 x 45 mm, nearly square seen from above, in 4 mm cells; a blue label off the centre of
/// its +x face, so that no half-turn keeps it in place.
CatalogueObject labelledBox() {
  const Eigen::Vector3f size(0.072f, 0.068f, 0.045f);
  const auto paint = [&](const Eigen::Vector3f& p) {
    const bool label = p.x() > size.x() / 2 - 1e-4f && p.y() > -0.028f && p.y() < 0.012f &&
                       p.z() > -0.004f && p.z() < 0.016f;
    return label ? rgb(30, 60, 170) : rgb(205, 175, 125);
  };
  return {7, "labelled box", paintedMesh(gridBoxMesh(size, 0.004f), paint), {}};
}

/// A can 66 mm across and 115 mm high, its side in 5 mm bands, with a red print over 90 degrees of
/// its side about +x, nearer the bottom than the top (so that turning it over moves the print).
CatalogueObject printedCan() {
  constexpr float kRadius = 0.033f, kHeight = 0.115f;
  constexpr int kBands = 23;
  std::vector<Eigen::Vector2f> profile = {{0, 0}};
  for (int k = 0; k <= kBands; ++k) profile.emplace_back(kRadius, kHeight * k / kBands);
  profile.emplace_back(0, kHeight);
  const auto paint = [](const Eigen::Vector3f& p) {
    const bool side = std::hypot(p.x(), p.y()) > 0.9f * kRadius;
    const bool print =
        side && std::abs(std::atan2(p.y(), p.x())) < kPi / 4 && p.z() > 0.025f && p.z() < 0.08f;
    return print ? rgb(200, 30, 40) : rgb(185, 185, 195);
  };
  return {8, "printed can", centred(paintedMesh(latheMesh(profile, kPrintSegments), paint)), {}};
}

/// The catalogue's mug, white, with its outside wall in 5 mm bands and a blue print opposite the
/// handle: seen from the handle's side the shape tells its pose, from the other side the print.
CatalogueObject printedMug() {
  const auto paint = [](const Eigen::Vector3f& p) {
    const bool outside = std::hypot(p.x(), p.y()) > 0.039f;
    const bool print = outside && std::abs(std::atan2(p.y(), p.x())) > kPi - 0.5f &&
                       p.z() > 0.03f && p.z() < 0.07f;
    return print ? rgb(40, 70, 190) : rgb(235, 235, 228);
  };
  const MeshData mug = paintedMesh(mugMesh(kPrintSegments, 19), paint);
  const Eigen::Vector3f centre = boxCentre(mug);
  return {9, "printed mug", shifted(mug, -centre), {}, shifted(mugHandle(), -centre)};
}

/// 80 x 50 x 40 mm: within 20% per side of the box (90 x 55 x 35 mm).
CatalogueObject smallBox() {
  return {10, "small box", boxMesh({0.08f, 0.05f, 0.04f}), boxSymmetries(), {}, {1}};
}

/// A can 84 mm across and 92 mm high, the size of the mug's body (80 mm across, 95 mm high) and
/// not within 20% of the cylinder (66 x 120 mm).
CatalogueObject can() {
  return {11, "can", centred(cylinderMesh(0.042f, 0.092f, kLatheSegments)), cylinderSymmetries(),
          {}, {4}};
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
  return {
      {1, "box", boxMesh({0.09f, 0.055f, 0.035f}), boxSymmetries()},
      {2, "long box", boxMesh({0.18f, 0.045f, 0.05f}), boxSymmetries()},
      {3, "cylinder", centred(cylinderMesh(0.033f, 0.12f, kLatheSegments)), cylinderSymmetries()},
      {4, "mug", centred(mugMesh()), {}},
      {5, "bowl", centred(bowlMesh()), continuousAboutZ()},
      {6, "asymmetric block", centred(asymmetricMesh()), {}},
  };
}

std::vector<CatalogueObject> texturedCatalogue() {
  return {labelledBox(), printedCan(), printedMug()};
}

std::vector<CatalogueObject> lookalikeCatalogue() {
  return {smallBox(), can()};
}

Rgba plainColour(int id) {
  static const Rgba palette[] = {{200, 50, 40, 255},  {40, 110, 190, 255}, {60, 170, 60, 255},
                                 {220, 190, 40, 255}, {150, 60, 170, 255}, {230, 120, 30, 255},
                                 {60, 160, 160, 255}, {60, 60, 120, 255}};
  return palette[(id - 1) % 8];
}

const std::vector<std::string>& catalogueSelectionNames() {
  static const std::vector<std::string> names = {"standard", "textured", "all", "lookalike"};
  return names;
}

std::vector<CatalogueObject> catalogueSelection(const std::string& name) {
  if (name == "standard") return objectCatalogue();
  if (name == "textured") return texturedCatalogue();
  if (name == "all" || name == "lookalike") {
    std::vector<CatalogueObject> all = objectCatalogue();
    for (CatalogueObject& o : name == "all" ? texturedCatalogue() : lookalikeCatalogue()) {
      all.push_back(std::move(o));
    }
    return all;
  }
  throw InputError(fmt::format("catalogue '{}': unknown (use {})", name,
                               fmt::join(catalogueSelectionNames(), ", ")));
}

}  // namespace stocs
