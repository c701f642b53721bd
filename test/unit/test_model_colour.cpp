// Model colour from files (PLY and PCD vertex colours, OBJ materials and textures baked into
// vertex colours), through model preparation (sample colours) and the model cache.
#include <assimp/scene.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "stocs/geometry/surface_sampling.h"
#include "stocs/io/mesh_io.h"
#include "stocs/io/ply_writer.h"
#include "stocs/model/model_cache.h"
#include "stocs/sim/shape_meshes.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

namespace fs = std::filesystem;
void writeText(const fs::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

std::string errorOf(const fs::path& file) {
  try {
    loadMesh(file.string(), 0.001f);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

/// A box in mm whose vertices on the +z side are red, the others blue, one of them unknown.
MeshData colouredBox() {
  MeshData box = boxMesh({100, 60, 40});
  for (const Eigen::Vector3f& v : box.vertices) {
    box.colours.push_back(v.z() > 0 ? Rgba(200, 30, 20, 255) : Rgba(40, 60, 220, 255));
  }
  box.colours[0] = Rgba(0, 0, 0, 0);
  return box;
}

TEST(ModelColour, PlyVertexColoursRoundTripAndAFileWithoutThemHasNone) {
  const fs::path dir = test::scratchDir("colour_ply");
  const MeshData box = colouredBox();
  writePly(dir / "box.ply", box);
  const MeshData read = loadMesh((dir / "box.ply").string(), 0.001f);
  EXPECT_EQ(read.colours, box.colours);
  MeshData plain = box;
  plain.colours.clear();
  writePly(dir / "plain.ply", plain);
  EXPECT_FALSE(loadMesh((dir / "plain.ply").string(), 0.001f).hasColour());
  // Red, green and blue without alpha: every colour known.
  writeText(dir / "rgb.ply",
            "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
            "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
            "end_header\n0 0 0 255 0 0\n100 0 0 1 2 3\n");
  const MeshData rgb = loadMesh((dir / "rgb.ply").string(), 0.001f);
  ASSERT_EQ(rgb.colours.size(), 2u);
  EXPECT_EQ(rgb.colours[0], Rgba(255, 0, 0, 255));
  EXPECT_EQ(rgb.colours[1], Rgba(1, 2, 3, 255));
}

TEST(ModelColour, PcdRgbAndRgbaFieldsAreReadAndAMalformedOneIsNamed) {
  const fs::path dir = test::scratchDir("colour_pcd");
  const std::string head =
      "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z {}\nSIZE 4 4 4 {}\nTYPE F F F "
      "U\nCOUNT 1 1 1 1\nWIDTH 3\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS "
      "3\nDATA ascii\n";
  const std::string body = "0 0 0 16711680\n0.1 0 0 65280\n0 0.05 0 {}\n";
  writeText(dir / "rgb.pcd",
            fmt::format(fmt::runtime(head), "rgb", 4) + fmt::format(fmt::runtime(body), 255));
  const MeshData rgb = loadMesh((dir / "rgb.pcd").string(), 1.0f);
  ASSERT_EQ(rgb.colours.size(), 3u);
  EXPECT_EQ(rgb.colours[0], Rgba(255, 0, 0, 255));
  EXPECT_EQ(rgb.colours[2], Rgba(0, 0, 255, 255));
  // rgba: alpha as stored, 0 (unknown) for the first two points.
  writeText(dir / "rgba.pcd", fmt::format(fmt::runtime(head), "rgba", 4) +
                                  fmt::format(fmt::runtime(body), 4278190335u));
  const MeshData rgba = loadMesh((dir / "rgba.pcd").string(), 1.0f);
  EXPECT_EQ(rgba.colours[1], Rgba(0, 255, 0, 0));
  EXPECT_EQ(rgba.colours[2], Rgba(0, 0, 255, 255));
  writeText(dir / "short.pcd",
            fmt::format(fmt::runtime(head), "rgb", 2) + "0 0 0 1\n0.1 0 0 2\n0 0.05 0 3\n");
  EXPECT_NE(errorOf(dir / "short.pcd").find("short.pcd: colour field 'rgb' is not 4 bytes"),
            std::string::npos)
      << errorOf(dir / "short.pcd");
}

const char kQuadObj[] =
    "v 0 0 0\nv 100 0 0\nv 100 50 0\nv 0 50 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "f 1/1 2/2 3/3 4/4\n";

/// An OBJ quad textured through its material: left half red, right half green.
fs::path writeLabelObj(const fs::path& dir) {
  cv::Mat texture(8, 16, CV_8UC3, cv::Scalar(0, 0, 255));  // BGR
  texture.colRange(8, 16).setTo(cv::Scalar(0, 255, 0));
  EXPECT_TRUE(cv::imwrite((dir / "label.png").string(), texture));
  writeText(dir / "label.mtl", "newmtl label\nKd 1 1 1\nmap_Kd label.png\n");
  writeText(dir / "label.obj", std::string("mtllib label.mtl\nusemtl label\n") + kQuadObj);
  return dir / "label.obj";
}

/// Expects writeLabelObj's quad subdivided and its texture baked into vertex colours.
void expectLabelBaked(const MeshData& baked) {
  // Edges up to 1 % of the 112 mm diagonal: about 100 x 100 cells per triangle.
  EXPECT_GT(baked.triangles.size(), 10000u);
  ASSERT_EQ(baked.colours.size(), baked.vertices.size());
  for (size_t i = 0; i < baked.vertices.size(); ++i) {
    const float x = baked.vertices[i].x();
    if (x < 0.04f) {
      ASSERT_EQ(baked.colours[i], Rgba(255, 0, 0, 255)) << x;
    } else if (x > 0.06f) {
      ASSERT_EQ(baked.colours[i], Rgba(0, 255, 0, 255)) << x;
    }
  }
}

TEST(ModelColour, ObjMaterialColourAndTextureBakedIntoVertexColours) {
  const fs::path dir = test::scratchDir("colour_obj");
  writeText(dir / "plain.obj", kQuadObj);
  EXPECT_FALSE(loadMesh((dir / "plain.obj").string(), 0.001f).hasColour());
  writeText(dir / "red.obj", std::string("mtllib red.mtl\nusemtl red\n") + kQuadObj);
  writeText(dir / "red.mtl", "newmtl red\nKd 1 0 0\n");
  const MeshData red = loadMesh((dir / "red.obj").string(), 0.001f);
  ASSERT_TRUE(red.hasColour());
  for (const Rgba& c : red.colours) EXPECT_EQ(c, Rgba(255, 0, 0, 255));

  const fs::path label = writeLabelObj(dir);
  expectLabelBaked(loadMesh(label.string(), 0.001f));
  writeText(dir / "lost.mtl", "newmtl lost\nmap_Kd lost.png\n");
  writeText(dir / "lost.obj", std::string("mtllib lost.mtl\nusemtl lost\n") + kQuadObj);
  EXPECT_NE(errorOf(dir / "lost.obj").find("lost.png: missing or unreadable"), std::string::npos)
      << errorOf(dir / "lost.obj");
}

// glTF and GLB through assimp's exporter: the texture as a file beside the glTF, or inside the GLB.
TEST(ModelColour, GltfAndGlbTexturesAreBakedAsTheObjs) {
  const fs::path dir = test::scratchDir("colour_gltf");
  const fs::path label = writeLabelObj(dir);
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(label.string(), 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  for (const char* format : {"gltf2", "glb2"}) {
    const fs::path file = dir / (std::string("label.") + (format[2] == 'b' ? "glb" : "gltf"));
    Assimp::Exporter exporter;
    ASSERT_EQ(exporter.Export(scene, format, file.string()), aiReturn_SUCCESS)
        << exporter.GetErrorString();
    expectLabelBaked(loadMesh(file.string(), 0.001f));
  }
}

TEST(ModelColour, SamplesCarryTheInterpolatedColourInTheUncolouredOrder) {
  MeshData box = colouredBox();
  for (Eigen::Vector3f& v : box.vertices) v *= 0.001f;
  MeshData plain = box;
  plain.colours.clear();
  const ObjectModel coloured = prepareModel(box, ModelSamplingParams{});
  const ObjectModel uncoloured = prepareModel(plain, ModelSamplingParams{});
  EXPECT_FALSE(uncoloured.hasColour());
  ASSERT_EQ(coloured.points, uncoloured.points);
  ASSERT_EQ(coloured.colours.size(), coloured.size());
  int unknown = 0;
  for (size_t i = 0; i < coloured.size(); ++i) {
    const Colour& c = coloured.colours[i];
    const Eigen::Vector3f& p = coloured.points[i];
    if (!isKnown(c)) {
      ++unknown;  // near the unknown corner, on the -z side
      EXPECT_LE(p.z(), 0);
      continue;
    }
    // The top face is red, the bottom blue; the sides away from the unknown corner (on the -x
    // and -y faces) blend linearly in z.
    if (p.x() < -0.049f || p.y() < -0.029f) continue;
    const float top = coloured.points[i].z() / 0.04f + 0.5f;
    EXPECT_NEAR(c.x(), (top * 200 + (1 - top) * 40) / 255, 0.01f) << coloured.points[i];
  }
  EXPECT_GT(unknown, 0);
  // A point model's samples take their own point's colour.
  Rng rng(3);
  MeshData points;
  points.vertices = sampleMeshSurface(box, 3000, rng).points;
  for (size_t i = 0; i < points.vertices.size(); ++i) {
    points.colours.push_back(i % 10 == 0                  ? Rgba(0, 0, 0, 0)
                             : points.vertices[i].z() > 0 ? Rgba(200, 30, 20, 255)
                                                          : Rgba(40, 60, 220, 255));
  }
  const ObjectModel thinned = prepareModel(points, ModelSamplingParams{});
  for (size_t i = 0; i < thinned.size(); ++i) {
    const auto v = std::find(points.vertices.begin(), points.vertices.end(), thinned.points[i]);
    ASSERT_NE(v, points.vertices.end());
    const Colour expected = toColour(points.colours[v - points.vertices.begin()]);
    EXPECT_EQ(isKnown(thinned.colours[i]), isKnown(expected));
    if (isKnown(expected)) {
      EXPECT_EQ(thinned.colours[i], expected);
    }
  }
  EXPECT_GT(std::count_if(thinned.colours.begin(), thinned.colours.end(),
                          [](const Colour& c) { return !isKnown(c); }),
            0);
  box.colours.pop_back();
  EXPECT_THROW(prepareModel(box, ModelSamplingParams{}), InputError);
}

TEST(ModelColour, TheCacheKeepsSampleColours) {
  const fs::path dir = test::scratchDir("colour_cache");
  writePly(dir / "box.ply", colouredBox());
  const ModelCache cache(dir / "cache");
  CacheReport first, second;
  const PreparedModel built = cache.load((dir / "box.ply").string(), 0.001f, {}, &first);
  const PreparedModel loaded = cache.load((dir / "box.ply").string(), 0.001f, {}, &second);
  EXPECT_EQ(first.outcome, CacheOutcome::kBuilt);
  EXPECT_EQ(second.outcome, CacheOutcome::kLoaded);
  ASSERT_EQ(loaded.model.colours.size(), built.model.colours.size());
  ASSERT_TRUE(built.model.hasColour());
  for (size_t i = 0; i < built.model.size(); ++i) {
    const Colour &a = built.model.colours[i], &b = loaded.model.colours[i];
    ASSERT_TRUE(isKnown(a) ? a == b : !isKnown(b)) << i;
  }
}

}  // namespace
}  // namespace stocs
