// Reading models from PLY and PCD, and the errors for bad files.
#include <gtest/gtest.h>

#include <fstream>

#include "stocs/error.h"
#include "stocs/mesh.h"
#include "test_support.h"

namespace stocs {
namespace {

void writeText(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file) << text;
}

std::string errorOf(const std::filesystem::path& file, float scale = 0.001f) {
  try {
    loadMesh(file.string(), scale);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MeshIo, ReadsAnAsciiMeshInMillimetres) {
  const auto dir = test::scratchDir("mesh_io_ascii");
  writePly(dir / "box.ply", boxMesh({100, 60, 40}));
  const MeshData m = loadMesh((dir / "box.ply").string(), 0.001f);
  ASSERT_EQ(m.vertices.size(), 8u);
  ASSERT_EQ(m.triangles.size(), 12u);
  EXPECT_NEAR(m.vertices[7].x(), 0.05f, 1e-6f);
  EXPECT_NEAR(pointSetDiameter(m.vertices), std::sqrt(0.01f + 0.0036f + 0.0016f), 1e-5f);
}

TEST(MeshIo, ReadsPointsOnlyPlyAndPcd) {
  const auto dir = test::scratchDir("mesh_io_points");
  MeshData box = boxMesh({0.1f, 0.06f, 0.04f});
  box.triangles.clear();
  writePly(dir / "points.ply", box);
  EXPECT_EQ(loadMesh((dir / "points.ply").string(), 1.0f).vertices.size(), 8u);
  writeText(dir / "points.pcd",
            "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH "
            "3\nHEIGHT 1\n"
            "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3\nDATA ascii\n0 0 0\n0.1 0 0\n0 0.05 0\n");
  const MeshData pcd = loadMesh((dir / "points.pcd").string(), 1.0f);
  EXPECT_EQ(pcd.vertices.size(), 3u);
  EXPECT_FALSE(pcd.isMesh());
}

TEST(MeshIo, BadFilesGiveErrorsNamingTheFileAndProblem) {
  const auto dir = test::scratchDir("mesh_io_bad");
  EXPECT_NE(errorOf(dir / "missing.ply").find("no such file"), std::string::npos);
  writeText(dir / "empty.ply", "");
  EXPECT_NE(errorOf(dir / "empty.ply").find("empty"), std::string::npos);
  writeText(dir / "garbage.ply", "this is not a ply file\n");
  EXPECT_NE(errorOf(dir / "garbage.ply").find("garbage.ply"), std::string::npos);
  writeText(dir / "model.obj", "v 0 0 0\n");
  EXPECT_NE(errorOf(dir / "model.obj").find("unsupported extension"), std::string::npos);
  writeText(dir / "no_vertices.ply",
            "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
            "property float z\nend_header\n");
  EXPECT_NE(errorOf(dir / "no_vertices.ply").find("no vertices"), std::string::npos);
  writeText(dir / "bad_face.ply",
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
            "end_header\n0 0 0\n50 0 0\n0 50 0\n3 0 1 7\n");
  EXPECT_NE(errorOf(dir / "bad_face.ply").find("refers to vertex 7"), std::string::npos);
  writeText(dir / "nan.ply",
            "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
            "property float z\nend_header\n0 0 0\nnan 1 1\n");
  EXPECT_NE(errorOf(dir / "nan.ply").find("non-finite"), std::string::npos);
}

TEST(MeshIo, UnitMistakesAreCaught) {
  const auto dir = test::scratchDir("mesh_io_units");
  writePly(dir / "box_mm.ply", boxMesh({100, 60, 40}));
  // A millimetre model declared as metres is 100 m long.
  EXPECT_NE(errorOf(dir / "box_mm.ply", 1.0f).find("unit scale"), std::string::npos);
  // A metre model declared as millimetres is 0.1 mm long.
  writePly(dir / "box_m.ply", boxMesh({0.1f, 0.06f, 0.04f}));
  EXPECT_NE(errorOf(dir / "box_m.ply", 0.001f).find("unit scale"), std::string::npos);
  EXPECT_NE(errorOf(dir / "box_m.ply", -1.0f).find("positive"), std::string::npos);
}

}  // namespace
}  // namespace stocs
