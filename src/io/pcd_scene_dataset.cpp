// With pcl_model.cpp, the only core file that includes PCL headers: PCD reading and PLY writing.
#include "stocs/io/pcd_scene_dataset.h"

#include <fmt/format.h>
#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_types.h>

#include <Eigen/Geometry>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "stocs/geometry/knn_index.h"
#include "stocs/geometry/organized_cloud.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/io/mesh_io.h"
#include "stocs/util/error.h"

namespace stocs {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr double kDepthScaleMm = 0.1;  // mm per depth unit: 16 bits reach 6.5 m
constexpr float kMaskToleranceM = 1e-4f;

struct PcdSceneSpec {
  fs::path model, scene;
  double metres_per_unit = 1;
  Eigen::Matrix4d scene_from_model = Eigen::Matrix4d::Identity();
};

PcdSceneSpec readSpec(const fs::path& dir) {
  const fs::path file = dir / "gt.json";
  const auto fail = [&](const std::string& why) {
    return InputError(fmt::format("{}: {}", file.string(), why));
  };
  PcdSceneSpec s;
  try {
    const json j = json::parse(readTextFile(file));
    s.model = dir / j.at("model").get<std::string>();
    s.scene = dir / j.at("scene").get<std::string>();
    const std::string units = j.value("units", "m");
    if (units != "m" && units != "mm") throw fail("units must be \"m\" or \"mm\"");
    s.metres_per_unit = units == "m" ? 1.0 : 0.001;
    const json& T = j.at("T_scene_from_model");
    for (int r = 0; r < 4; ++r) {
      if (T.size() != 4 || T.at(r).size() != 4) throw fail("T_scene_from_model must be 4x4");
      for (int c = 0; c < 4; ++c) s.scene_from_model(r, c) = T.at(r).at(c).get<double>();
    }
  } catch (const json::exception& e) {
    throw fail(e.what());
  }
  return s;
}

pcl::PointCloud<pcl::PointXYZRGBA> loadOrganizedScene(const fs::path& file) {
  pcl::PointCloud<pcl::PointXYZRGBA> cloud;
  const pcl::console::VERBOSITY_LEVEL saved = pcl::console::getVerbosityLevel();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const int rc = pcl::io::loadPCDFile(file.string(), cloud);
  pcl::console::setVerbosityLevel(saved);
  if (rc != 0) throw InputError(fmt::format("{}: cannot read the PCD file", file.string()));
  if (cloud.height < 2) {
    throw InputError(fmt::format("{}: the scene is not an organized cloud", file.string()));
  }
  return cloud;
}

void writeImage(const fs::path& file, const cv::Mat& image) {
  fs::create_directories(file.parent_path());
  if (!cv::imwrite(file.string(), image)) {
    throw InputError(fmt::format("{}: cannot write", file.string()));
  }
}

void writeJson(const fs::path& file, const json& j) {
  fs::create_directories(file.parent_path());
  std::ofstream out(file);
  if (!(out << j.dump() << '\n')) throw InputError(fmt::format("{}: cannot write", file.string()));
}

json flat(const Eigen::MatrixXd& m) {
  json a = json::array();
  for (int r = 0; r < m.rows(); ++r) {
    for (int c = 0; c < m.cols(); ++c) a.push_back(m(r, c));
  }
  return a;
}

}  // namespace

bool isPcdSceneFolder(const fs::path& dir) {
  std::error_code ec;
  if (!fs::exists(dir / "gt.json", ec) || fs::exists(dir / "models", ec)) return false;
  try {
    return json::parse(readTextFile(dir / "gt.json")).contains("T_scene_from_model");
  } catch (const std::exception&) {
    return false;
  }
}

int convertPcdSceneToBop(const fs::path& dir, const fs::path& out) {
  const PcdSceneSpec spec = readSpec(dir);
  const pcl::PointCloud<pcl::PointXYZRGBA> scene = loadOrganizedScene(spec.scene);
  const float to_m = static_cast<float>(spec.metres_per_unit);

  OrganizedCloud cloud(static_cast<int>(scene.width), static_cast<int>(scene.height));
  cv::Mat depth(cloud.height, cloud.width, CV_16UC1, cv::Scalar(0));
  cv::Mat rgb(cloud.height, cloud.width, CV_8UC3, cv::Scalar(0, 0, 0));
  for (int i = 0; i < static_cast<int>(scene.size()); ++i) {
    const pcl::PointXYZRGBA& p = scene[i];
    rgb.at<cv::Vec3b>(i / cloud.width, i % cloud.width) = cv::Vec3b(p.b, p.g, p.r);
    if (!std::isfinite(p.z) || p.z <= 0) continue;
    cloud.points[i] = Eigen::Vector3f(p.x, p.y, p.z) * to_m;
    const double units = cloud.points[i].z() * 1000.0 / kDepthScaleMm;
    if (units < 65535) depth.at<uint16_t>(i / cloud.width, i % cloud.width) = std::lround(units);
  }
  const CameraIntrinsics k = intrinsicsFromCloud(cloud);

  const MeshData model = loadMesh(spec.model.string(), to_m);
  const Eigen::Matrix3d R = spec.scene_from_model.topLeftCorner<3, 3>();
  const Eigen::Vector3d t = spec.scene_from_model.topRightCorner<3, 1>() * spec.metres_per_unit;
  std::vector<Eigen::Vector3f> placed;
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3f& v : model.vertices) {
    placed.push_back((R * v.cast<double>() + t).cast<float>());
    box.extend(v.cast<double>());
  }
  // BOP models have their origin at the bounding box centre; rotation errors then turn the object
  // about itself (PCL's milk model is in scene coordinates, a metre from its own origin).
  const Eigen::Vector3d centre = box.center();
  const KnnIndex index(placed);
  cv::Mat mask(cloud.height, cloud.width, CV_8UC1, cv::Scalar(0));
  std::vector<size_t> nn;
  std::vector<float> d2;
  int mask_pixels = 0;
  for (int i = 0; i < static_cast<int>(cloud.points.size()); ++i) {
    if (!cloud.isValid(i)) continue;
    index.knn(cloud.points[i], 1, nn, d2);
    if (d2[0] <= kMaskToleranceM * kMaskToleranceM) {
      mask.at<uint8_t>(i / cloud.width, i % cloud.width) = 255;
      ++mask_pixels;
    }
  }

  const fs::path scene_dir = out / "test" / "000000";
  writeImage(scene_dir / "depth" / "000000.png", depth);
  writeImage(scene_dir / "rgb" / "000000.png", rgb);
  writeImage(scene_dir / "mask_visib" / "000000_000000.png", mask);
  Eigen::Matrix3d K;
  K << k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1;
  writeJson(scene_dir / "scene_camera.json",
            {{"0", {{"cam_K", flat(K)}, {"depth_scale", kDepthScaleMm}}}});
  writeJson(scene_dir / "scene_gt.json",
            {{"0", json::array({{{"cam_R_m2c", flat(R)},
                                 {"cam_t_m2c", flat((R * centre + t) * 1000.0)},
                                 {"obj_id", 1}}})}});
  pcl::PointCloud<pcl::PointXYZ> model_mm;
  for (const Eigen::Vector3f& v : model.vertices) {
    const Eigen::Vector3f p = (v.cast<double>() - centre).cast<float>() * 1000.0f;
    model_mm.push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  }
  fs::create_directories(out / "models");
  const fs::path model_file = out / "models" / "obj_000001.ply";
  if (pcl::PLYWriter().write(model_file.string(), model_mm, false, false) != 0) {
    throw InputError(fmt::format("{}: cannot write", model_file.string()));
  }
  writeJson(out / "models" / "models_info.json",
            {{"1", {{"diameter", pointSetDiameter(model.vertices) * 1000.0}}}});
  return mask_pixels;
}

}  // namespace stocs
