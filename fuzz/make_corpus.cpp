// Writes the seed corpus of every fuzz target: `stocs_fuzz_make_corpus <fuzz/corpus>` creates
// <fuzz/corpus>/<target>/seed_* (tiny valid inputs, made here so no third-party data is copied).
#include <fmt/format.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <vector>

#include "fuzz_support.h"
#include "model_cache_setup.h"
#include "ros_message_layout.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/sim/shape_meshes.h"

namespace fs = std::filesystem;
using stocs::fuzz::ByteWriter;

namespace {

void writeSeed(const fs::path& corpus, const std::string& target, const std::string& name,
               const std::string& bytes) {
  stocs::fuzz::writeInput(corpus / target / ("seed_" + name),
                          reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
}

std::string fileBytes(const fs::path& file) {
  return stocs::readTextFile(file);
}

std::string pngBytes(const cv::Mat& image) {
  std::vector<uint8_t> png;
  cv::imencode(".png", image, png);
  return {png.begin(), png.end()};
}

void modelSeeds(const fs::path& corpus) {
  const fs::path scratch = stocs::fuzz::scratchDir();
  stocs::writePly(scratch / "box.ply", stocs::boxMesh({0.06f, 0.04f, 0.03f}), 1000.0f, 2);
  writeSeed(corpus, "fuzz_ply_model", "ascii_mesh.ply", fileBytes(scratch / "box.ply"));
  ByteWriter binary;
  binary.append(
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float "
      "y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n");
  const float corners[4][3] = {{0, 0, 0}, {50, 0, 0}, {0, 50, 0}, {0, 0, 50}};
  for (const auto& c : corners) binary.put(c[0]).put(c[1]).put(c[2]);
  for (const int32_t f : {0, 1, 2, 0, 2, 3}) {
    if (f == 0) binary.put(uint8_t{3});
    binary.put(f);
  }
  writeSeed(corpus, "fuzz_ply_model", "binary_mesh.ply", binary.bytes());

  const std::string pcd_header =
      "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 4\n"
      "HEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\n";
  writeSeed(corpus, "fuzz_pcd_model", "ascii.pcd",
            pcd_header + "DATA ascii\n0 0 0\n0.05 0 0\n0 0.05 0\n0 0 0.05\n");
  ByteWriter pcd_binary;
  pcd_binary.append(pcd_header + "DATA binary\n");
  for (const auto& c : corners) pcd_binary.put(c[0] / 1000).put(c[1] / 1000).put(c[2] / 1000);
  writeSeed(corpus, "fuzz_pcd_model", "binary.pcd", pcd_binary.bytes());
}

/// glTF JSON of one triangle whose 36 bytes of positions are buffer 0 at `uri` (none: GLB's own).
std::string gltfJson(const std::string& uri) {
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], )"
         R"("nodes": [{"mesh": 0, "translation": [0, 0, 10]}], "meshes": [{"primitives": [)"
         R"({"attributes": {"POSITION": 0}}]}], "accessors": [{"bufferView": 0, "count": 3, )"
         R"("type": "VEC3", "componentType": 5126, "min": [0, 0, 0], "max": [50, 50, 0]}], )"
         R"("bufferViews": [{"buffer": 0, "byteLength": 36}], "buffers": [{"byteLength": 36)" +
         (uri.empty() ? std::string() : R"(, "uri": ")" + uri + "\"") + "}]}";
}

/// Seeds of fuzz_mesh_model: the first byte picks the format (0 OBJ, 1 STL, 2 DAE, 3 glTF, 4 GLB).
void meshSeeds(const fs::path& corpus) {
  const std::string t = "fuzz_mesh_model";
  writeSeed(corpus, t, "quad.obj",
            std::string(1, '\0') +
                "mtllib gone.mtl\no quad\nv 0 0 0\nv 50 0 0\nv 50 50 0\n"
                "v 0 50 10\nusemtl red\nf 1 2 3 4\n");
  writeSeed(corpus, t, "ascii.stl",
            "\1solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 50 0 0\n"
            "vertex 0 50 0\nendloop\nendfacet\nendsolid t\n");
  const float triangle[9] = {0, 0, 0, 50, 0, 0, 0, 50, 0};
  ByteWriter stl;
  stl.append("\1" + std::string(80, ' ')).put(uint32_t{1}).put(0.0f).put(0.0f).put(1.0f);
  for (const float x : triangle) stl.put(x);
  writeSeed(corpus, t, "binary.stl", stl.put(uint16_t{0}).bytes());
  writeSeed(
      corpus, t, "nodes.dae",
      "\2<?xml version=\"1.0\"?><COLLADA xmlns=\"http://www.collada.org/2005/11/"
      "COLLADASchema\" version=\"1.4.1\"><asset><unit meter=\"1\"/><up_axis>Z_UP"
      "</up_axis></asset><library_geometries><geometry id=\"g\"><mesh><source id=\"p\">"
      "<float_array id=\"a\" count=\"9\">0 0 0 50 0 0 0 50 0</float_array>"
      "<technique_common><accessor source=\"#a\" count=\"3\" stride=\"3\"><param name=\"X\" "
      "type=\"float\"/><param name=\"Y\" type=\"float\"/><param name=\"Z\" type=\"float\"/>"
      "</accessor></technique_common></source><vertices id=\"v\"><input semantic=\"POSITION\" "
      "source=\"#p\"/></vertices><triangles count=\"1\"><input semantic=\"VERTEX\" "
      "source=\"#v\" offset=\"0\"/><p>0 1 2</p></triangles></mesh></geometry>"
      "</library_geometries><library_visual_scenes><visual_scene id=\"s\"><node id=\"n\">"
      "<translate>0 0 10</translate><instance_geometry url=\"#g\"/></node></visual_scene>"
      "</library_visual_scenes><scene><instance_visual_scene url=\"#s\"/></scene></COLLADA>");
  writeSeed(corpus, t, "embedded.gltf",
            "\3" + gltfJson("data:application/octet-stream;base64,"
                            "AAAAAAAAAAAAAAAAAABIQgAAAAAAAAAAAAAAAAAASEIAAAAA"));
  std::string json = gltfJson("");
  json.resize((json.size() + 3) / 4 * 4, ' ');  // chunks are 4-byte aligned
  ByteWriter glb;
  glb.append("\4glTF").put(uint32_t{2}).put(static_cast<uint32_t>(12 + 8 + json.size() + 8 + 36));
  glb.put(static_cast<uint32_t>(json.size())).append("JSON").append(json);
  glb.put(uint32_t{36}).append(std::string("BIN\0", 4));
  for (const float x : triangle) glb.put(x);
  writeSeed(corpus, t, "triangle.glb", glb.bytes());
}

void bopSeeds(const fs::path& corpus) {
  writeSeed(corpus, "fuzz_bop_json", "scene_camera.json",
            R"({"0": {"cam_K": [572.4, 0.0, 325.3, 0.0, 573.6, 242.0, 0.0, 0.0, 1.0],)"
            R"( "depth_scale": 0.1}, "1": {"cam_K": [500, 0, 320, 0, 500, 240, 0, 0, 1]}})");
  writeSeed(corpus, "fuzz_bop_json", "scene_gt.json",
            R"({"0": [{"cam_R_m2c": [1, 0, 0, 0, 1, 0, 0, 0, 1], "cam_t_m2c": [10, -20, 700],)"
            R"( "obj_id": 2}], "1": []})");
  writeSeed(corpus, "fuzz_bop_json", "models_info.json",
            R"({"1": {"diameter": 102.1, "symmetries_discrete": [[-1, 0, 0, 0, 0, -1, 0, 0, 0, )"
            R"(0, 1, 0, 0, 0, 0, 1]]}, "2": {"diameter": 80, "symmetries_continuous": )"
            R"([{"axis": [0, 0, 1], "offset": [0, 0, 0]}]}, "3": {"diameter": 50.5}})");
  writeSeed(corpus, "fuzz_bop_targets", "targets.json",
            R"([{"scene_id": 1, "im_id": 0, "obj_id": 2, "inst_count": 1},)"
            R"( {"scene_id": 1, "im_id": 0, "obj_id": 5, "inst_count": 0},)"
            R"( {"scene_id": 2, "im_id": 3, "obj_id": 1, "inst_count": 3}])");
  writeSeed(corpus, "fuzz_lookalikes", "lookalikes.json", R"({"pairs": [[1, 10], [4, 11]]})");
  writeSeed(corpus, "fuzz_box_detections", "boxes.json",
            R"([{"scene_id": 1, "image_id": 0, "category_id": 2, "bbox": [10, 5, 20.5, 30],)"
            R"( "score": 0.9, "time": 0.1}, {"scene_id": 1, "image_id": 0, "category_id": 5,)"
            R"( "bbox": [-4, 40, 80, 20], "score": 0.3}])");
  writeSeed(corpus, "fuzz_param_file", "settings.yaml",
            "flag: true\ncount: 3\nshare: 0.25\nseconds: 2.5\nname: net.onnx\n"
            "names: [mug, '-', bowl]\nmode: b\n");
  writeSeed(corpus, "fuzz_bop_results", "results.csv",
            "scene_id,im_id,obj_id,score,R,t,time\n"
            "1,0,2,0.8,1 0 0 0 1 0 0 0 1,10 -20 700,1.5\n"
            "1,3,1,0.25,0 -1 0 1 0 0 0 0 1,0 0 650.5,-1\n");

  cv::Mat depth(3, 4, CV_16UC1);
  cv::randu(depth, 0, 2000);
  writeSeed(corpus, "fuzz_images", "depth16.png", pngBytes(depth));
  cv::Mat prob16(3, 4, CV_16UC1);
  cv::randu(prob16, 0, 10001);
  writeSeed(corpus, "fuzz_images", "probability16.png", pngBytes(prob16));
  cv::Mat edge(3, 4, CV_8UC1, cv::Scalar(255));
  edge.at<uint8_t>(1, 2) = 0;
  writeSeed(corpus, "fuzz_images", "boundary8.png", pngBytes(edge));
}

void cacheSeeds(const fs::path& corpus) {
  const fs::path dir = stocs::fuzz::scratchDir() / "seed_cache";
  const std::string model = stocs::fuzz::writeCacheFuzzModel(dir);
  const stocs::ModelCache cache(dir / "cache");
  stocs::CacheReport report;
  const stocs::PreparedModel prepared =
      cache.load(model, stocs::fuzz::kCacheModelUnitScale, stocs::fuzz::cacheFuzzParams(), &report);
  const std::string entry = fileBytes(report.entry);
  writeSeed(corpus, "fuzz_model_cache", "entry", std::string(1, '\0') + entry);
  writeSeed(corpus, "fuzz_model_cache", "payload",
            std::string(1, '\1') + entry.substr(sizeof(stocs::fuzz::CacheEntryHeader)));
  std::ostringstream map(std::ios::binary);
  ByteWriter ppf;
  ppf.put(static_cast<uint16_t>(prepared.model.size()));
  prepared.ppf_map.write(map);
  writeSeed(corpus, "fuzz_ppf_map", "box_map", ppf.append(map.str()).bytes());
}

ByteWriter cloudHeader(uint32_t width, uint32_t height, uint32_t point_step, uint32_t row_step) {
  ByteWriter w;
  w.put(width).put(height).put(point_step).put(row_step);
  return w;
}

void rosSeeds(const fs::path& corpus) {
  constexpr uint8_t kFloat32 = 7;  // sensor_msgs::PointField::FLOAT32
  ByteWriter xyz = cloudHeader(2, 2, 12, 24);
  xyz.put(uint8_t{3});
  for (uint8_t a = 0; a < 3; ++a) xyz.put(a).put(uint32_t{4u * a}).put(kFloat32).put(uint32_t{1});
  for (int i = 0; i < 4; ++i) xyz.put(0.01f * i).put(-0.02f).put(i == 3 ? NAN : 0.6f);
  writeSeed(corpus, "fuzz_ros_cloud", "xyz_2x2", xyz.bytes());
  // x y z rgb with 4 padding bytes at each row end.
  ByteWriter padded = cloudHeader(2, 2, 16, 36);
  padded.put(uint8_t{4});
  for (uint8_t a = 0; a < 4; ++a)
    padded.put(a).put(uint32_t{4u * a}).put(kFloat32).put(uint32_t{1});
  for (int i = 0; i < 18; ++i) padded.put(0.1f * i);
  writeSeed(corpus, "fuzz_ros_cloud", "xyzrgb_padded", padded.bytes());

  // Encoding indices into kImageEncodings: 1 mono16, 3 8UC3, 0 mono8, 7 32FC1.
  const auto image = [](uint32_t w, uint32_t h, uint32_t step, uint8_t encoding, uint8_t channels) {
    ByteWriter m;
    m.put(w).put(h).put(step).put(encoding).put(channels);
    m.put(w).put(h).put(uint32_t{0}).put(uint32_t{0});
    m.put(500.0).put(500.0).put(w / 2.0).put(h / 2.0);
    return m;
  };
  ByteWriter depth = image(2, 2, 4, 1, 1);
  for (const uint16_t d : {700, 0, 650, 1200}) depth.put(d);
  writeSeed(corpus, "fuzz_ros_image", "depth_mono16", depth.bytes());
  ByteWriter colour = image(2, 1, 6, 3, 3);
  for (uint8_t v = 0; v < 6; ++v) colour.put(static_cast<uint8_t>(v * 40));
  writeSeed(corpus, "fuzz_ros_image", "channels_8uc3", colour.bytes());
  ByteWriter boundary = image(3, 2, 3, 0, 1);
  for (const uint8_t v : {255, 0, 255, 255, 255, 0}) boundary.put(v);
  writeSeed(corpus, "fuzz_ros_image", "boundary_mono8", boundary.bytes());
  ByteWriter prob = image(2, 2, 8, 7, 1);
  for (const float p : {0.0f, 0.5f, 1.0f, 0.25f}) prob.put(p);
  writeSeed(corpus, "fuzz_ros_image", "probability_32fc1", prob.bytes());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    fmt::print(stderr, "usage: {} <corpus folder>\n", argv[0]);
    return 2;
  }
  const fs::path corpus = argv[1];
  modelSeeds(corpus);
  meshSeeds(corpus);
  bopSeeds(corpus);
  cacheSeeds(corpus);
  rosSeeds(corpus);
  return 0;
}
