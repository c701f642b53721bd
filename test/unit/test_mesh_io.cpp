// Reading models from PLY and PCD, and the errors for bad files.
#include <gtest/gtest.h>

#include <fstream>

#include "stocs/io/mesh_io.h"
#include "stocs/util/error.h"
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
  // PCL's PLYWriter declares an empty face element without properties for point clouds.
  writeText(dir / "pcl_points.ply",
            "ply\nformat ascii 1.0\ncomment PCL generated\nelement vertex 2\nproperty float "
            "x\nproperty float y\nproperty float z\nelement face 0\nend_header\n0 0 0\n0.1 0 "
            "0\n");
  EXPECT_EQ(loadMesh((dir / "pcl_points.ply").string(), 1.0f).vertices.size(), 2u);
  const MeshData pcd = loadMesh((dir / "points.pcd").string(), 1.0f);
  EXPECT_EQ(pcd.vertices.size(), 3u);
  EXPECT_FALSE(pcd.isMesh());
}

TEST(MeshIo, BinaryPcdDataThatLooksLikeAHeaderLineIsRefused) {
  // PCL's parser would read on past DATA into such data and crash (found by fuzz_pcd_model).
  const auto dir = test::scratchDir("mesh_io_pcd_body");
  std::string text =
      "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 4\nHEIGHT 1\n"
      "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA binary\n\nCOLUMNS a\n";
  text.append(48, '\0');
  writeText(dir / "body.pcd", text);
  EXPECT_NE(errorOf(dir / "body.pcd").find("PCD binary data begins like the header line 'COLUMNS'"),
            std::string::npos);
}

TEST(MeshIo, AsciiPcdDataThatLooksLikeAHeaderLineIsRefused) {
  // PCL's parser read "POINTS 4" and "DATA0" after DATA as header and threw std::out_of_range on
  // the kind-less DATA line (found by fuzz_pcd_model).
  const auto dir = test::scratchDir("mesh_io_pcd_ascii_body");
  writeText(
      dir / "body.pcd",
      "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 4\nHEIGHT 1\n"
      "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA ascii\nPOINTS 4\nDATA0\n0 0.0;5 0\n0 0 0.05\n");
  EXPECT_NE(errorOf(dir / "body.pcd").find("PCD ascii data begins like the header line 'POINTS'"),
            std::string::npos);
}

TEST(MeshIo, BadFilesGiveErrorsNamingTheFileAndProblem) {
  const auto dir = test::scratchDir("mesh_io_bad");
  EXPECT_NE(errorOf(dir / "missing.ply").find("no such file"), std::string::npos);
  writeText(dir / "empty.ply", "");
  EXPECT_NE(errorOf(dir / "empty.ply").find("empty"), std::string::npos);
  writeText(dir / "garbage.ply", "this is not a ply file\n");
  EXPECT_NE(errorOf(dir / "garbage.ply").find("garbage.ply"), std::string::npos);
  writeText(dir / "model.xyz", "0 0 0\n");
  EXPECT_NE(errorOf(dir / "model.xyz").find("unsupported extension"), std::string::npos);
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

std::string binaryTetrahedron(const std::string& header) {
  std::string body;
  const float corners[12] = {0, 0, 0, 50, 0, 0, 0, 50, 0, 0, 0, 50};
  body.append(reinterpret_cast<const char*>(corners), sizeof corners);
  for (const int32_t i : {0, 1, 2, 0, 2, 3}) {
    if (i == 0) body.push_back(3);
    body.append(reinterpret_cast<const char*>(&i), sizeof i);
  }
  return header + body;
}

const std::string kBinaryPlyHeader =
    "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float "
    "y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";

TEST(MeshIo, ReadsBinaryPlyAndBopStyleAsciiHeaders) {
  const auto dir = test::scratchDir("mesh_io_headers");
  writeText(dir / "binary.ply", binaryTetrahedron(kBinaryPlyHeader));
  const MeshData binary = loadMesh((dir / "binary.ply").string(), 0.001f);
  EXPECT_EQ(binary.vertices.size(), 4u);
  EXPECT_EQ(binary.triangles.size(), 2u);
  writeText(dir / "bop.ply",
            "ply\nformat ascii 1.0\ncomment VCGLIB generated\nelement vertex 3\nproperty float x\n"
            "property float y\nproperty float z\nproperty float nx\nproperty float ny\n"
            "property float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
            "property uchar alpha\nelement face 1\nproperty list uchar int vertex_indices\n"
            "end_header\n0 0 0 0 0 1 10 20 30 255\n50 0 0 0 0 1 10 20 30 255\n"
            "0 50 0 0 0 1 10 20 30 255\n3 0 1 2\n");
  const MeshData bop = loadMesh((dir / "bop.ply").string(), 0.001f);
  EXPECT_EQ(bop.vertices.size(), 3u);
  EXPECT_EQ(bop.triangles.size(), 1u);
  EXPECT_EQ(bop.colours, std::vector<Rgba>(3, {10, 20, 30, 255}));
}

// Regression (fuzz_ply_model): PCL's PLY reader aborts on an assert for list properties outside a
// face element and trusts element counts, so such headers must be rejected before PCL sees them.
TEST(MeshIo, PlyHeadersPclCannotHandleAreRejected) {
  const auto dir = test::scratchDir("mesh_io_ply_headers");
  std::string nul_name = kBinaryPlyHeader;
  nul_name.replace(nul_name.find("face"), 4, std::string("\0\0\0 f", 5));
  writeText(dir / "nul.ply", binaryTetrahedron(nul_name));
  EXPECT_NE(errorOf(dir / "nul.ply").find("header line 7 is not text"), std::string::npos);
  std::string list_in_vertex = kBinaryPlyHeader;
  list_in_vertex.replace(list_in_vertex.find("element face 2\n"), 15, "");
  writeText(dir / "list_in_vertex.ply", binaryTetrahedron(list_in_vertex));
  EXPECT_NE(errorOf(dir / "list_in_vertex.ply").find("single values"), std::string::npos);
  std::string other_element = kBinaryPlyHeader;
  other_element.replace(other_element.find("face"), 4, "edge");
  writeText(dir / "edge.ply", binaryTetrahedron(other_element));
  EXPECT_NE(errorOf(dir / "edge.ply").find("only 'vertex' and 'face'"), std::string::npos);
  std::string huge = kBinaryPlyHeader;
  huge.replace(huge.find("vertex 4"), 8, "vertex 4000000");
  writeText(dir / "huge.ply", binaryTetrahedron(huge));
  EXPECT_NE(errorOf(dir / "huge.ply").find("4000000 vertices need at least 48000002 bytes"),
            std::string::npos);
}

// Regression (fuzz_pcd_model): PCL's PCD reader dereferenced null for binary data behind an
// unknown header keyword or blank and indented lines, allocated ~100 TB for a field of COUNT 0,
// and trusts POINTS; such headers are rejected before PCL sees the file.
TEST(MeshIo, PcdHeadersPclCannotHandleAreRejected) {
  const auto dir = test::scratchDir("mesh_io_pcd_headers");
  const std::string header =
      "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 4\n"
      "HEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA binary\n";
  const float points[12] = {0, 0, 0, 0.05f, 0, 0, 0, 0.05f, 0, 0, 0, 0.05f};
  const std::string body(reinterpret_cast<const char*>(points), sizeof points);
  writeText(dir / "good.pcd", header + body);
  EXPECT_EQ(loadMesh((dir / "good.pcd").string(), 1.0f).vertices.size(), 4u);
  std::string unknown = header;
  unknown.replace(unknown.find("VERSION"), 7, "VEON");
  writeText(dir / "unknown.pcd", unknown + body);
  EXPECT_NE(errorOf(dir / "unknown.pcd", 1.0f).find("unknown PCD header keyword 'VEON'"),
            std::string::npos);
  writeText(dir / "short.pcd", header + body.substr(0, 40));
  EXPECT_NE(errorOf(dir / "short.pcd", 1.0f).find("4 points need at least 48 bytes"),
            std::string::npos);
  std::string indented = header;
  indented.replace(indented.find("VERSION"), 0, "\n\t");
  writeText(dir / "indented.pcd", indented + body);
  EXPECT_NE(errorOf(dir / "indented.pcd", 1.0f).find("line 2 is blank or indented"),
            std::string::npos);
  std::string no_count = header;
  no_count.replace(no_count.find("COUNT 1"), 7, "COUNT 0");
  writeText(dir / "no_count.pcd", no_count + body);
  EXPECT_NE(errorOf(dir / "no_count.pcd", 1.0f).find("field 'x' has COUNT 0"), std::string::npos);
  std::string mismatch = header;
  mismatch.replace(mismatch.find("WIDTH 4"), 7, "WIDTH 3");
  writeText(dir / "mismatch.pcd", mismatch + body);
  EXPECT_NE(errorOf(dir / "mismatch.pcd", 1.0f).find("WIDTH x HEIGHT is not POINTS"),
            std::string::npos);
}

}  // namespace
}  // namespace stocs
