// The project's own meshes: closed and outward-wound, the right size and symmetries, and meshes/
// in the repository exactly what `stocs meshes` writes; the textured objects' prints break the
// symmetries of their shapes.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include "stocs/io/bop_dataset.h"
#include "stocs/io/mesh_io.h"
#include "stocs/sim/bop_writer.h"
#include "stocs/sim/shape_meshes.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

/// Every directed edge appears once and its reverse once: closed, with consistent winding.
void expectClosedAndConsistent(const MeshData& mesh, const std::string& name) {
  std::map<std::pair<int, int>, int> edges;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  }
  int bad = 0;
  for (const auto& [edge, count] : edges) {
    const auto reverse = edges.find({edge.second, edge.first});
    bad += count != 1 || reverse == edges.end() || reverse->second != 1;
  }
  EXPECT_EQ(bad, 0) << name << ": edges not shared by exactly two opposite triangles";
}

/// Volume by the divergence theorem: positive for an outward-wound closed mesh.
double signedVolume(const MeshData& mesh) {
  double v = 0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    v += mesh.vertices[t[0]].cast<double>().dot(
             mesh.vertices[t[1]].cast<double>().cross(mesh.vertices[t[2]].cast<double>())) /
         6;
  }
  return v;
}

/// Whether `transform` (BOP symmetry, mm) maps every vertex onto a vertex of the mesh.
bool mapsOntoItself(const MeshData& mesh, const Eigen::Matrix4d& transform) {
  for (const Eigen::Vector3f& v : mesh.vertices) {
    const Eigen::Vector3d moved = transform.topLeftCorner<3, 3>() * v.cast<double>() +
                                  transform.topRightCorner<3, 1>() / 1000;
    double nearest = 1e9;
    for (const Eigen::Vector3f& w : mesh.vertices) {
      nearest = std::min(nearest, (w.cast<double>() - moved).norm());
    }
    if (nearest > 1e-6) return false;
  }
  return true;
}

/// The mesh with coinciding vertices (to 0.1 um) merged: the shape of a painted mesh.
MeshData welded(const MeshData& mesh) {
  MeshData out;
  std::map<std::tuple<long, long, long>, int> index;
  std::vector<int> merged;
  for (const Eigen::Vector3f& v : mesh.vertices) {
    const Eigen::Vector3f q = v * 1e7f;
    const auto key = std::make_tuple(std::lround(q.x()), std::lround(q.y()), std::lround(q.z()));
    const auto [it, added] = index.emplace(key, static_cast<int>(out.vertices.size()));
    if (added) out.vertices.push_back(v);
    merged.push_back(it->second);
  }
  for (const Eigen::Vector3i& t : mesh.triangles) {
    out.triangles.emplace_back(merged[t[0]], merged[t[1]], merged[t[2]]);
  }
  return out;
}

/// Mean position of the vertices whose colour is not the first vertex's (the body's): the print.
Eigen::Vector3d printCentre(const MeshData& mesh) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int count = 0;
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (mesh.colours[i] == mesh.colours[0]) continue;
    sum += mesh.vertices[i].cast<double>();
    ++count;
  }
  return count > 0 ? Eigen::Vector3d(sum / count) : Eigen::Vector3d::Constant(NAN);
}

Eigen::Vector3d meanPosition(const MeshData& mesh) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3f& v : mesh.vertices) sum += v.cast<double>();
  return sum / static_cast<double>(mesh.vertices.size());
}

std::string fileBytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Closed (where painted, once coinciding vertices are merged), outward, centred on its bounding
/// box and of a graspable size.
void expectCentredSolid(const CatalogueObject& o) {
  expectClosedAndConsistent(welded(o.mesh), o.name);
  EXPECT_GT(signedVolume(o.mesh), 0) << o.name << " is wound inside out";
  Eigen::Vector3f lo = o.mesh.vertices[0], hi = lo;
  for (const Eigen::Vector3f& v : o.mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  EXPECT_LT(((lo + hi) / 2).norm(), 1e-6f) << o.name;
  EXPECT_GT(pointSetDiameter(o.mesh.vertices), 0.05f) << o.name;
  EXPECT_LT(pointSetDiameter(o.mesh.vertices), 0.25f) << o.name;
}

TEST(ObjectCatalogue, EveryMeshIsClosedOutwardAndCentred) {
  const std::vector<CatalogueObject> objects = objectCatalogue();
  ASSERT_EQ(objects.size(), 6u);
  for (size_t i = 0; i < objects.size(); ++i) {
    EXPECT_EQ(objects[i].id, static_cast<int>(i) + 1);
    expectCentredSolid(objects[i]);
  }
}

TEST(ObjectCatalogue, VolumesMatchTheShapes) {
  const std::vector<CatalogueObject> objects = objectCatalogue();
  EXPECT_NEAR(signedVolume(objects[0].mesh), 0.09 * 0.055 * 0.035, 1e-9);
  // A 48-gon prism: area (n/2) r^2 sin(2 pi / n), a little less than the circle.
  const double polygon = 24 * 0.033 * 0.033 * std::sin(2 * M_PI / 48);
  EXPECT_NEAR(signedVolume(objects[2].mesh), polygon * 0.12, 1e-8);
  // The mug's material (wall, bottom, handle) is far less than its outer cylinder.
  EXPECT_LT(signedVolume(objects[3].mesh), 0.3 * M_PI * 0.04 * 0.04 * 0.095);
  // A solid composed of parts: the asymmetric block is the box plus the corner block.
  EXPECT_NEAR(signedVolume(objects[5].mesh), 0.1 * 0.06 * 0.04 + 0.04 * 0.04 * 0.03, 1e-9);
}

TEST(ObjectCatalogue, DeclaredSymmetriesHoldAndAsymmetricShapesHaveNone) {
  for (const CatalogueObject& o : objectCatalogue()) {
    for (const Eigen::Matrix4d& m : o.symmetries.symmetries_discrete) {
      EXPECT_TRUE(mapsOntoItself(o.mesh, m)) << o.name;
    }
    for (const ContinuousSymmetry& s : o.symmetries.symmetries_continuous) {
      // A turn by one lathe segment maps the lathe onto itself.
      Eigen::Matrix4d turn = Eigen::Matrix4d::Identity();
      turn.topLeftCorner<3, 3>() = Eigen::AngleAxisd(2 * M_PI / 48, s.axis).toRotationMatrix();
      EXPECT_TRUE(mapsOntoItself(o.mesh, turn)) << o.name;
    }
  }
  // The mug's handle and the asymmetric block's corner break every half-turn.
  for (int index : {3, 5}) {
    const CatalogueObject o = objectCatalogue()[index];
    EXPECT_FALSE(o.symmetries.symmetric()) << o.name;
    for (int axis = 0; axis < 3; ++axis) {
      Eigen::Matrix4d half_turn = Eigen::Matrix4d::Identity();
      half_turn.topLeftCorner<3, 3>() =
          Eigen::AngleAxisd(M_PI, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
      EXPECT_FALSE(mapsOntoItself(o.mesh, half_turn)) << o.name << " axis " << axis;
    }
  }
}

TEST(ObjectCatalogue, CommittedMeshesAreWhatTheGeneratorWrites) {
  const auto dir = test::scratchDir("regenerated");
  writeModels(dir, objectCatalogue());
  const std::filesystem::path committed = "meshes";  // tests run in the repository root
  ASSERT_TRUE(std::filesystem::is_directory(committed));
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::filesystem::path name = entry.path().filename();
    ++files;
    EXPECT_EQ(fileBytes(committed / name), fileBytes(entry.path()))
        << name << " differs from the generator's output; run `stocs meshes --out meshes`";
    EXPECT_LT(std::filesystem::file_size(entry.path()), 1000000u) << name;
  }
  EXPECT_EQ(files, 7);
}

TEST(TexturedCatalogue, ClosedOutwardCentredColouredAndWithoutSymmetries) {
  const std::vector<CatalogueObject> objects = texturedCatalogue();
  ASSERT_EQ(objects.size(), 3u);
  for (size_t i = 0; i < objects.size(); ++i) {
    const CatalogueObject& o = objects[i];
    EXPECT_EQ(o.id, static_cast<int>(i) + 7);
    expectCentredSolid(o);
    ASSERT_EQ(o.mesh.colours.size(), o.mesh.vertices.size()) << o.name;
    for (const VertexColour& c : o.mesh.colours) ASSERT_EQ(c[3], 255) << o.name;
    EXPECT_FALSE(o.symmetries.symmetric()) << o.name << ": the print is kept by no symmetry";
    EXPECT_TRUE(printCentre(o.mesh).allFinite()) << o.name << " has no print";
  }
  EXPECT_EQ(catalogueSelection("all").size(), 9u);
  EXPECT_EQ(catalogueSelection("standard").size(), 6u);
  EXPECT_THROW(catalogueSelection("plain"), InputError);
}

TEST(TexturedCatalogue, ThePrintsBreakTheSymmetriesOfTheShapes) {
  const std::vector<CatalogueObject> objects = texturedCatalogue();
  const auto turn = [](double deg, int axis) {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m.topLeftCorner<3, 3>() =
        Eigen::AngleAxisd(deg * M_PI / 180, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
    return m;
  };
  // The box's half-turns and its near symmetry, the quarter turn about z (4 mm off); the can's
  // half-turn across its axis and turns about it: each moves the print by more than 1 cm.
  struct ShapeSymmetry {
    size_t object;
    Eigen::Matrix4d transform;
    bool exact;  ///< maps the shape onto itself
  };
  const std::vector<ShapeSymmetry> shape_symmetries = {
      {0, turn(180, 0), true}, {0, turn(180, 1), true}, {0, turn(180, 2), true},
      {0, turn(90, 2), false}, {1, turn(180, 0), true}, {1, turn(90, 2), true},
      {1, turn(180, 2), true}};
  for (const ShapeSymmetry& s : shape_symmetries) {
    const CatalogueObject& o = objects[s.object];
    if (s.exact) {
      EXPECT_TRUE(mapsOntoItself(welded(o.mesh), s.transform)) << o.name;
    }
    const Eigen::Vector3d print = printCentre(o.mesh);
    EXPECT_GT((s.transform.topLeftCorner<3, 3>() * print - print).norm(), 0.01) << o.name << "\n"
                                                                                << s.transform;
  }
  // The mug's print is on the side away from its handle.
  const CatalogueObject& mug = objects[2];
  ASSERT_FALSE(mug.handle.vertices.empty());
  EXPECT_GT(meanPosition(mug.handle).x(), 0.03);
  EXPECT_LT(printCentre(mug.mesh).x(), -0.02);
  EXPECT_TRUE(objects[0].handle.vertices.empty());
}

TEST(ObjectCatalogue, WrittenModelsReadBackWithTheirInfo) {
  const auto root = test::scratchDir("dataset");
  std::filesystem::create_directories(root / "models");
  std::filesystem::create_directories(root / "test");
  const std::vector<CatalogueObject> objects = catalogueSelection("all");
  writeModels(root / "models", objects);
  const BopDataset dataset(root);
  const std::map<int, BopObjectInfo> info = dataset.modelsInfo();
  ASSERT_EQ(info.size(), objects.size());
  for (const CatalogueObject& o : objects) {
    const MeshData read = loadMesh(dataset.modelPath(o.id).string(), 0.001f);
    ASSERT_EQ(read.vertices.size(), o.mesh.vertices.size());
    ASSERT_EQ(read.triangles, o.mesh.triangles);
    for (size_t i = 0; i < read.vertices.size(); ++i) {
      ASSERT_LT((read.vertices[i] - o.mesh.vertices[i]).norm(), 1e-6f);
    }
    EXPECT_NEAR(info.at(o.id).diameter_mm, pointSetDiameter(o.mesh.vertices) * 1000, 1e-3);
    EXPECT_EQ(info.at(o.id).symmetries_discrete.size(), o.symmetries.symmetries_discrete.size());
    EXPECT_EQ(info.at(o.id).symmetries_continuous.size(),
              o.symmetries.symmetries_continuous.size());
  }
  EXPECT_NEAR(info.at(1).diameter_mm, std::sqrt(90.0 * 90 + 55 * 55 + 35 * 35), 1e-3);
}

TEST(ShapeMeshes, LathePolesAndTubeCapsCloseTheMesh) {
  const MeshData cone = latheMesh({{0, 0}, {0.05f, 0}, {0, 0.1f}}, 16);
  EXPECT_EQ(cone.vertices.size(), 1u + 16 + 1);
  expectClosedAndConsistent(cone, "cone");
  EXPECT_NEAR(signedVolume(cone), 8 * 0.05 * 0.05 * std::sin(2 * M_PI / 16) * 0.1 / 3, 1e-9);
  const MeshData tube = tubeArcMesh(0.05f, 0.01f, 0, static_cast<float>(M_PI), 32, 16);
  expectClosedAndConsistent(tube, "tube");
  // Half a torus: (pi R) (pi r^2), a little less for the polygonal cross-section.
  EXPECT_NEAR(signedVolume(tube), M_PI * 0.05 * M_PI * 0.01 * 0.01, 0.03 * signedVolume(tube));
}

}  // namespace
}  // namespace stocs
