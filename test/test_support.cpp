#include "test_support.h"

#include <sys/wait.h>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "stocs/depth_renderer.h"

namespace stocs::test {

std::filesystem::path datasetsDir() {
  std::string dir;
  if (const char* env = std::getenv("STOCS_DATASETS"); env && *env) {
    dir = env;
  } else {
    dir = STOCS_DATASETS_DEFAULT;
  }
  if (dir.empty()) return {};
  if (!std::filesystem::is_directory(dir)) {
    ADD_FAILURE() << "STOCS_DATASETS is set to '" << dir << "' but that folder does not exist";
    return {};
  }
  return dir;
}

std::filesystem::path scratchDir(const std::string& name) {
  // One folder per test: ctest runs the tests of a file as parallel processes.
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string test =
      info ? std::string(info->test_suite_name()) + "." + info->name() : "no_test";
  const std::filesystem::path dir =
      std::filesystem::path(STOCS_TEST_BINARY_DIR) / "scratch" / test / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

MeshData boxMesh(const Eigen::Vector3f& size) {
  MeshData m;
  const Eigen::Vector3f h = size / 2;
  for (int i = 0; i < 8; ++i) {
    m.vertices.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                            (i & 4) ? h.z() : -h.z());
  }
  // Each face as a quad of corner indices in counter-clockwise order seen from outside.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.emplace_back(q[0], q[1], q[2]);
    m.triangles.emplace_back(q[0], q[2], q[3]);
  }
  return m;
}

MeshData latheMesh(const std::vector<Eigen::Vector2f>& profile, int segments) {
  MeshData m;
  const int rings = static_cast<int>(profile.size());
  for (const Eigen::Vector2f& rz : profile) {
    for (int s = 0; s < segments; ++s) {
      const float a = 2.0f * static_cast<float>(M_PI) * s / segments;
      m.vertices.emplace_back(rz.x() * std::cos(a), rz.x() * std::sin(a), rz.y());
    }
  }
  for (int r = 0; r + 1 < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const int a = r * segments + s, b = r * segments + (s + 1) % segments;
      const int c = (r + 1) * segments + (s + 1) % segments, d = (r + 1) * segments + s;
      m.triangles.emplace_back(a, b, c);
      m.triangles.emplace_back(a, c, d);
    }
  }
  return m;
}

void writePly(const std::filesystem::path& file, const MeshData& mesh, float scale) {
  std::ofstream out(file);
  out << "ply\nformat ascii 1.0\nelement vertex " << mesh.vertices.size()
      << "\nproperty float x\nproperty float y\nproperty float z\n";
  if (!mesh.triangles.empty()) {
    out << "element face " << mesh.triangles.size() << "\nproperty list uchar int vertex_indices\n";
  }
  out << "end_header\n";
  for (const Eigen::Vector3f& v : mesh.vertices)
    out << v.x() * scale << ' ' << v.y() * scale << ' ' << v.z() * scale << '\n';
  for (const Eigen::Vector3i& t : mesh.triangles)
    out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
}

cv::Mat renderDepth(const std::vector<PlacedMesh>& objects, const CameraIntrinsics& camera,
                    cv::Mat* labels) {
  DepthRenderer renderer(camera);
  for (size_t o = 0; o < objects.size(); ++o)
    renderer.draw(objects[o].mesh, objects[o].pose, static_cast<int>(o) + 1);
  if (labels) *labels = renderer.labels().clone();
  return renderer.depth().clone();
}

MeshData asymmetricMesh() {
  MeshData base = boxMesh({0.1f, 0.06f, 0.04f});
  const MeshData block = boxMesh({0.04f, 0.04f, 0.03f});
  const int offset = static_cast<int>(base.vertices.size());
  for (const Eigen::Vector3f& v : block.vertices)
    base.vertices.push_back(v + Eigen::Vector3f(0.03f, 0.01f, 0.035f));
  for (const Eigen::Vector3i& t : block.triangles)
    base.triangles.push_back(t + Eigen::Vector3i::Constant(offset));
  return base;
}

Eigen::Isometry3f viewingPose(float distance) {
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.linear() = (Eigen::AngleAxisf(2.5f, Eigen::Vector3f::UnitX()) *
                   Eigen::AngleAxisf(0.6f, Eigen::Vector3f::UnitZ()) *
                   Eigen::AngleAxisf(0.3f, Eigen::Vector3f::UnitY()))
                      .toRotationMatrix();
  pose.translation() = Eigen::Vector3f(0.02f, -0.01f, distance);
  return pose;
}

CameraIntrinsics testCamera() {
  CameraIntrinsics k;
  k.fx = k.fy = 300;
  k.cx = 160;
  k.cy = 120;
  k.width = 320;
  k.height = 240;
  return k;
}

Eigen::Isometry3f writeSyntheticBopDataset(const std::filesystem::path& root) {
  namespace fs = std::filesystem;
  const fs::path scene = root / "test" / "000000";
  for (const char* sub : {"depth", "prob"}) fs::create_directories(scene / sub);
  fs::create_directories(root / "models");
  const MeshData mesh = asymmetricMesh();
  writePly(root / "models" / "obj_000001.ply", mesh, 1000.0f);
  const CameraIntrinsics k = testCamera();
  const Eigen::Isometry3f pose = viewingPose(0.6f);
  cv::Mat labels;
  const cv::Mat depth = renderDepth({{mesh, pose}}, k, &labels);
  cv::Mat depth16, prob16;
  depth.convertTo(depth16, CV_16UC1, 10000.0);  // 0.1 mm per unit
  prob16 = cv::Mat(labels.size(), CV_16UC1, cv::Scalar(0));
  prob16.setTo(9000, labels == 1);
  cv::imwrite((scene / "depth" / "000000.png").string(), depth16);
  cv::imwrite((scene / "prob" / "000000_000001.png").string(), prob16);
  std::ofstream(scene / "scene_camera.json")
      << R"({"0": {"cam_K": [300, 0, 160, 0, 300, 120, 0, 0, 1], "depth_scale": 0.1}})";
  std::ostringstream gt;
  gt << R"({"0": [{"cam_R_m2c": [)";
  for (int i = 0; i < 9; ++i) gt << (i ? ", " : "") << pose.linear()(i / 3, i % 3);
  gt << R"(], "cam_t_m2c": [)" << pose.translation().x() * 1000 << ", "
     << pose.translation().y() * 1000 << ", " << pose.translation().z() * 1000
     << R"(], "obj_id": 1}]})";
  std::ofstream(scene / "scene_gt.json") << gt.str();
  std::ofstream(root / "models" / "models_info.json")
      << R"({"1": {"diameter": )" << pointSetDiameter(mesh.vertices) * 1000 << "}}";
  return pose;
}

int runCommand(const std::string& command, std::string& output) {
  output.clear();
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return -1;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) output.append(buffer.data(), n);
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace stocs::test
