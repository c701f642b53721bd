#include "test_support.h"

#include <unistd.h>

#include <sys/wait.h>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "stocs/sim/depth_renderer.h"
#include "stocs/sim/synthetic_dataset.h"

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

std::string fileBytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::map<std::string, std::string> treeFiles(const std::filesystem::path& root) {
  std::map<std::string, std::string> out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(root)) {
    if (e.is_regular_file())
      out[std::filesystem::relative(e.path(), root).string()] = fileBytes(e.path());
  }
  return out;
}

std::filesystem::path scratchDir(const std::string& name) {
  // One folder per test: ctest runs the tests of a file as parallel processes.
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  // Outside a test (SetUpTestSuite) every process of the suite runs the same code: one folder each.
  const std::string test = info ? std::string(info->test_suite_name()) + "." + info->name()
                                : "suite_setup_" + std::to_string(::getpid());
  const std::filesystem::path dir =
      std::filesystem::path(STOCS_TEST_BINARY_DIR) / "scratch" / test / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

cv::Mat renderDepth(const std::vector<PlacedMesh>& objects, const CameraIntrinsics& camera,
                    cv::Mat* labels) {
  DepthRenderer renderer(camera);
  for (size_t o = 0; o < objects.size(); ++o)
    renderer.draw(objects[o].mesh, objects[o].pose, static_cast<int>(o) + 1);
  if (labels) *labels = renderer.labels().clone();
  return renderer.depth().clone();
}

CameraIntrinsics smallCamera() {
  return {200, 200, 79.5, 59.5, 160, 120};
}

CameraIntrinsics testCamera() {
  return {300, 300, 160, 120, 320, 240};
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

void writeThreeObjectScene(const std::filesystem::path& root) {
  SyntheticDatasetParams params;
  params.layout.objects = 3;
  params.layout.distractors = 1;
  params.seed = 11;
  writeSyntheticDataset(root, params);
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

std::vector<std::map<std::string, std::string>> readCsv(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<std::string> names;
  std::vector<std::map<std::string, std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
    if (names.empty()) {
      names = cells;
      continue;
    }
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < cells.size() && i < names.size(); ++i) row[names[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
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
