// Models in the mesh formats read through assimp (OBJ, STL, DAE, glTF, GLB): materials, node
// transforms, COLLADA units and up axis, the project's own meshes in every format, and the errors
// for bad files.
#include <gtest/gtest.h>

#include <assimp/scene.h>
#include <fmt/format.h>
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <set>
#include <tuple>

#include "stocs/io/mesh_io.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

namespace fs = std::filesystem;

void writeBytes(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary) << bytes;
}

std::string errorOf(const fs::path& file, float scale = 0.001f) {
  try {
    loadMesh(file.string(), scale);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

/// The distinct triangle corners of `mesh`, rounded to a micrometre: the surface whatever the
/// vertex order, sharing or numbering of the format.
std::set<std::tuple<long, long, long>> cornerSet(const MeshData& mesh) {
  std::set<std::tuple<long, long, long>> out;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3f& p = mesh.vertices[t[k]];
      out.emplace(std::lround(p.x() * 1e6), std::lround(p.y() * 1e6), std::lround(p.z() * 1e6));
    }
  }
  return out;
}

bool hasVertex(const MeshData& mesh, const Eigen::Vector3f& p) {
  for (const Eigen::Vector3f& v : mesh.vertices) {
    if ((v - p).norm() < 1e-6f) return true;
  }
  return false;
}

const char kQuadObj[] = "v 0 0 0\nv 100 0 0\nv 100 50 0\nv 0 50 20\nf 1 2 3 4\n";

TEST(MeshFormats, ObjReadsWithOrWithoutItsMtl) {
  const fs::path dir = test::scratchDir("formats_obj");
  writeBytes(dir / "plain.obj", kQuadObj);
  const MeshData plain = loadMesh((dir / "plain.obj").string(), 0.001f);
  EXPECT_EQ(plain.triangles.size(), 2u);  // the quad, triangulated
  EXPECT_TRUE(hasVertex(plain, {0.1f, 0.05f, 0}));
  writeBytes(dir / "no_mtl.obj", std::string("mtllib gone.mtl\nusemtl red\n") + kQuadObj);
  EXPECT_EQ(cornerSet(loadMesh((dir / "no_mtl.obj").string(), 0.001f)), cornerSet(plain));
  writeBytes(dir / "with_mtl.obj", std::string("mtllib here.mtl\nusemtl red\n") + kQuadObj);
  writeBytes(dir / "here.mtl", "newmtl red\nKd 1 0 0\n");
  EXPECT_EQ(cornerSet(loadMesh((dir / "with_mtl.obj").string(), 0.001f)), cornerSet(plain));
}

TEST(MeshFormats, AsciiAndBinaryStlGiveTheSameSurface) {
  const fs::path dir = test::scratchDir("formats_stl");
  const float corners[4][3] = {{0, 0, 0}, {50, 0, 0}, {0, 50, 0}, {0, 0, 50}};
  const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::string ascii = "solid tetra\n", binary(80, ' ');
  const uint32_t count = 4;
  binary.append(reinterpret_cast<const char*>(&count), 4);
  for (const auto& f : faces) {
    ascii += "facet normal 0 0 0\nouter loop\n";
    const float normal[3] = {0, 0, 0};
    binary.append(reinterpret_cast<const char*>(normal), sizeof normal);
    for (const int i : f) {
      ascii += fmt::format("vertex {} {} {}\n", corners[i][0], corners[i][1], corners[i][2]);
      binary.append(reinterpret_cast<const char*>(corners[i]), sizeof corners[i]);
    }
    ascii += "endloop\nendfacet\n";
    binary.append(2, '\0');  // attribute byte count
  }
  writeBytes(dir / "ascii.stl", ascii + "endsolid tetra\n");
  writeBytes(dir / "binary.stl", binary);
  const MeshData a = loadMesh((dir / "ascii.stl").string(), 0.001f);
  const MeshData b = loadMesh((dir / "binary.stl").string(), 0.001f);
  EXPECT_EQ(a.triangles.size(), 4u);
  EXPECT_EQ(b.triangles.size(), 4u);
  EXPECT_EQ(cornerSet(a), cornerSet(b));
  EXPECT_TRUE(hasVertex(a, {0, 0, 0.05f}));
}

/// A COLLADA file in mm with Z up: a triangle in the first node, and one translated by 30 mm
/// along z in the second.
std::string zUpDaeInMillimetres() {
  auto geometry = [](const std::string& id, const std::string& positions) {
    return fmt::format(
        R"(<geometry id="{0}"><mesh><source id="{0}-p"><float_array id="{0}-a" count="9">{1})"
        R"(</float_array><technique_common><accessor source="#{0}-a" count="3" stride="3">)"
        R"(<param name="X" type="float"/><param name="Y" type="float"/>)"
        R"(<param name="Z" type="float"/></accessor></technique_common></source>)"
        R"(<vertices id="{0}-v"><input semantic="POSITION" source="#{0}-p"/></vertices>)"
        R"(<triangles count="1"><input semantic="VERTEX" source="#{0}-v" offset="0"/>)"
        R"(<p>0 1 2</p></triangles></mesh></geometry>)",
        id, positions);
  };
  return R"(<?xml version="1.0" encoding="utf-8"?>)"
         R"(<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">)"
         R"(<asset><unit name="millimeter" meter="0.001"/><up_axis>Z_UP</up_axis></asset>)"
         "<library_geometries>" +
         geometry("a", "0 0 0 100 0 0 0 50 0") + geometry("b", "0 0 0 10 0 0 0 0 20") +
         R"(</library_geometries><library_visual_scenes><visual_scene id="s">)"
         R"(<node id="na"><instance_geometry url="#a"/></node>)"
         R"(<node id="nb"><translate>0 0 30</translate><instance_geometry url="#b"/></node>)"
         R"(</visual_scene></library_visual_scenes>)"
         R"(<scene><instance_visual_scene url="#s"/></scene></COLLADA>)";
}

// As rviz and MoveIt read a DAE: its <unit> applies, assimp's turn of Z_UP to Y-up does not.
TEST(MeshFormats, DaeKeepsItsUnitAndFrameAndMergesItsNodes) {
  const fs::path dir = test::scratchDir("formats_dae");
  writeBytes(dir / "parts.dae", zUpDaeInMillimetres());
  const MeshData m = loadMesh((dir / "parts.dae").string(), 1.0f);
  ASSERT_EQ(m.triangles.size(), 2u);
  for (const Eigen::Vector3f& p : {Eigen::Vector3f(0.1f, 0, 0), Eigen::Vector3f(0, 0.05f, 0),
                                   Eigen::Vector3f(0, 0, 0.03f), Eigen::Vector3f(0, 0, 0.05f)}) {
    EXPECT_TRUE(hasVertex(m, p)) << p.transpose();
  }
}

/// `mesh` written by assimp's exporter in `format` (an assimp format id) as `file`.
void exportWithAssimp(const fs::path& ply, const std::string& format, const fs::path& file) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(ply.string(), 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  Assimp::Exporter exporter;
  ASSERT_EQ(exporter.Export(scene, format, file.string()), aiReturn_SUCCESS)
      << exporter.GetErrorString();
}

TEST(MeshFormats, TheProjectsMeshesLoadFromEveryFormat) {
  const fs::path dir = test::scratchDir("formats_catalogue");
  const std::vector<std::pair<std::string, std::string>> formats = {
      {"obj", ".obj"},     {"stl", ".stl"},    {"stlb", ".stl"},
      {"collada", ".dae"}, {"gltf2", ".gltf"}, {"glb2", ".glb"}};
  for (const CatalogueObject& object : objectCatalogue()) {
    const fs::path ply = dir / fmt::format("obj_{:06d}.ply", object.id);
    writePly(ply, object.mesh, 1000.0f);
    const MeshData reference = loadMesh(ply.string(), 0.001f);
    for (const auto& [format, ext] : formats) {
      const fs::path file = dir / fmt::format("{}_{}{}", object.name, format, ext);
      exportWithAssimp(ply, format, file);
      const MeshData read = loadMesh(file.string(), 0.001f);
      EXPECT_EQ(read.triangles.size(), reference.triangles.size()) << file;
      EXPECT_EQ(cornerSet(read), cornerSet(reference)) << file;
      // The exporter writes the white material assimp gives a PLY without colour; STL has none.
      EXPECT_EQ(read.hasColour(), ext != ".stl") << file;
      for (const Rgba& c : read.colours) ASSERT_EQ(c, Rgba(255, 255, 255, 255)) << file;
    }
  }
}

// A unit mistake names the unit the file is likely in, whatever its format.
TEST(MeshFormats, ImplausibleSizesNameTheLikelyUnit) {
  const fs::path dir = test::scratchDir("formats_units");
  writeBytes(dir / "mm.obj", kQuadObj);  // 10 cm across, in mm
  EXPECT_NE(errorOf(dir / "mm.obj", 1.0f).find("if the file is in mm use unit scale 0.001"),
            std::string::npos);
  writeBytes(dir / "m.obj", "v 0 0 0\nv 0.1 0 0\nv 0.1 0.05 0\nf 1 2 3\n");  // in metres
  EXPECT_NE(errorOf(dir / "m.obj", 0.001f).find("if the file is in m use unit scale 1 "),
            std::string::npos);
  writeBytes(dir / "cm.obj", "v 0 0 0\nv 12 0 0\nv 12 8 0\nf 1 2 3\n");  // 12 cm, in cm
  EXPECT_NE(errorOf(dir / "cm.obj", 1.0f).find("if the file is in cm use unit scale 0.01"),
            std::string::npos);
  writePly(dir / "mm.ply", boxMesh({100, 60, 40}));
  EXPECT_NE(errorOf(dir / "mm.ply", 1.0f).find("if the file is in mm use unit scale 0.001"),
            std::string::npos);
}

TEST(MeshFormats, BadMeshFilesGiveErrorsNamingTheFileAndProblem) {
  const fs::path dir = test::scratchDir("formats_bad");
  auto expectError = [&](const std::string& name, const std::string& bytes,
                         const std::string& problem) {
    writeBytes(dir / name, bytes);
    const std::string error = errorOf(dir / name);
    EXPECT_NE(error.find("model " + (dir / name).string() + ": "), std::string::npos) << error;
    EXPECT_NE(error.find(problem), std::string::npos) << name << ": " << error;
  };
  expectError("bad_index.obj", "v 0 0 0\nv 50 0 0\nv 0 50 0\nf 1 2 9\n",
              "not a readable OBJ file (OBJ: vertex index out of range)");
  expectError("nan.obj", "v nan 0 0\nv 50 0 0\nv 0 50 0\nf 1 2 3\n", "non-finite coordinate");
  expectError("comments_only.obj", std::string(200, '#') + "\n", "not a readable OBJ file");
  expectError("bad_ascii.stl", "solid x\nfacet normal a b c\nouter loop\nvertex 1 2\n",
              "not a readable STL file");
  std::string truncated(80, ' ');
  truncated += std::string("\xe8\x03\0\0", 4) + std::string(50, '\0');  // 1000 facets claimed
  expectError("truncated.stl", truncated, "not a readable STL file");
  std::string huge(80, ' ');
  huge += std::string("\xff\xff\xff\xff", 4) + std::string(50, '\0');
  expectError("huge.stl", huge, "not a readable STL file");
  expectError("no_facets.stl", std::string(80, ' ') + std::string(4, '\0'),
              "not a readable STL file");
  expectError("truncated.dae", "<?xml version=\"1.0\"?>\n<COLLADA version=\"1.4.1\"><asset>",
              "not a readable DAE file");
  expectError("short.glb", "glTF", "not a binary glTF (no glTF header)");
  // Headers whose lengths assimp would allocate (found by fuzz_mesh_model): 1.7 GB claimed.
  const std::string header("glTF\x02\0\0\0", 8);
  expectError("long.glb", header + std::string("\xc8\x01\x68\x65", 4) + std::string(20, '\0'),
              "binary glTF header gives 1701315016 bytes, the file has 32");
  expectError("long_chunk.glb",
              header + std::string("\x1c\0\0\0", 4) + std::string("\xff\xff\0\0JSON", 8) +
                  std::string(8, ' '),
              "binary glTF chunk at byte 12 runs past the file's end");
  // A glTF accessor claiming a billion vertices in a 12-byte buffer.
  expectError("huge.gltf",
              R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], )"
              R"("nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": )"
              R"({"POSITION": 0}}]}], "accessors": [{"count": 1000000000, "type": "VEC3", )"
              R"("componentType": 5126, "bufferView": 0}], "bufferViews": [{"buffer": 0, )"
              R"("byteLength": 12}], "buffers": [{"byteLength": 12, "uri": )"
              R"("data:application/octet-stream;base64,AAAAAAAAAAAAAAAA"}]})",
              "is out of range");
}

/// Writes the fuzz_mesh_model input fuzz/known_crashes/`name` as the model file `to` (the input's
/// first byte picks the format); false when the test does not run in the source folder.
bool writeKnownCrash(const std::string& name, const fs::path& to) {
  std::ifstream in("fuzz/known_crashes/" + name, std::ios::binary);
  if (!in) return false;
  const std::string input((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  writeBytes(to, input.substr(1));
  return true;
}

// A malformed COLLADA file on which Debian's assimp 5.2.5 reads address 0 (found by
// fuzz_mesh_model): the reader's crash becomes an error naming the file, and the process goes on
// reading models.
TEST(MeshFormats, AReaderCrashGivesAnErrorNamingTheFile) {
  const fs::path dir = test::scratchDir("formats_crash");
  ASSERT_TRUE(writeKnownCrash("assimp_dae_null_read", dir / "crash.dae"));
  const std::string error = errorOf(dir / "crash.dae");
  // "crashed (signal 11: ...)"; under AddressSanitizer, which catches the SEGV, "failed (exit
  // code 1)".
  EXPECT_NE(error.find("model " + (dir / "crash.dae").string() + ": the mesh reader "),
            std::string::npos)
      << error;
  EXPECT_NE(error.find(" reading this file"), std::string::npos) << error;
  writeBytes(dir / "quad.obj", kQuadObj);
  EXPECT_EQ(loadMesh((dir / "quad.obj").string(), 0.001f).triangles.size(), 2u);
}

// A COLLADA accessor declaring billions of values (found by fuzz_mesh_model): assimp asks for tens
// of gigabytes. The reader's capped address space makes it fail (a Release build), or the parent's
// deadline ends it (under AddressSanitizer, which the cap would break): an error naming the file,
// and the process goes on reading models.
TEST(MeshFormats, AColladaArrayOfBillionsGivesAnErrorNamingTheFile) {
  const fs::path dir = test::scratchDir("formats_huge_array");
  ASSERT_TRUE(writeKnownCrash("assimp_dae_huge_array", dir / "huge.dae"));
  const std::string error = errorOf(dir / "huge.dae");
  EXPECT_EQ(error.rfind("model " + (dir / "huge.dae").string() + ": ", 0), 0u) << error;
  writeBytes(dir / "quad.obj", kQuadObj);
  EXPECT_EQ(loadMesh((dir / "quad.obj").string(), 0.001f).triangles.size(), 2u);
}

// assimp's formats are read by a program of its own (stocs_mesh_reader, started with posix_spawn:
// a forked copy of a multi-threaded node may not run assimp). One that cannot start is named.
TEST(MeshFormats, AMeshReaderThatCannotStartIsNamed) {
  const fs::path dir = test::scratchDir("formats_no_reader");
  writeBytes(dir / "quad.obj", kQuadObj);
  ASSERT_EQ(setenv("STOCS_MESH_READER", "/nonexistent/stocs_mesh_reader", 1), 0);
  const std::string error = errorOf(dir / "quad.obj");
  unsetenv("STOCS_MESH_READER");
  EXPECT_NE(error.find("model " + (dir / "quad.obj").string() +
                       ": cannot start the mesh reader /nonexistent/stocs_mesh_reader: No such "
                       "file or directory"),
            std::string::npos)
      << error;
  EXPECT_EQ(loadMesh((dir / "quad.obj").string(), 0.001f).triangles.size(), 2u);
}

}  // namespace
}  // namespace stocs
