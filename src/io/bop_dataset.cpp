#include "stocs/io/bop_dataset.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "stocs/io/probability_image.h"
#include "stocs/util/error.h"

namespace stocs {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json parseJsonFile(const fs::path& path) {
  try {
    return json::parse(readTextFile(path));
  } catch (const json::exception& e) {
    throw InputError(fmt::format("{}: invalid JSON: {}", path.string(), e.what()));
  }
}

int parseId(const fs::path& file, const std::string& key) {
  try {
    size_t used = 0;
    const int id = std::stoi(key, &used);
    if (used == key.size() && id >= 0) return id;
  } catch (const std::exception&) {
  }
  throw InputError(fmt::format("{}: key '{}' is not a non-negative image id", file.string(), key));
}

template <int N>
Eigen::Matrix<double, N, 1> numbers(const fs::path& file, const json& j, const char* field) {
  if (!j.is_object() || !j.contains(field)) {
    throw InputError(fmt::format("{}: entry lacks '{}'", file.string(), field));
  }
  const json& a = j.at(field);
  if (!a.is_array() || a.size() != N) {
    throw InputError(
        fmt::format("{}: '{}' must be an array of {} numbers", file.string(), field, N));
  }
  Eigen::Matrix<double, N, 1> v;
  for (int k = 0; k < N; ++k) {
    if (!a[k].is_number() || !std::isfinite(a[k].get<double>())) {
      throw InputError(
          fmt::format("{}: '{}' element {} is not a finite number", file.string(), field, k));
    }
    v[k] = a[k].get<double>();
  }
  return v;
}

double scalar(const fs::path& file, const json& j, const char* field) {
  if (!j.is_object() || !j.contains(field) || !j.at(field).is_number() ||
      !std::isfinite(j.at(field).get<double>())) {
    throw InputError(fmt::format("{}: entry lacks a finite number '{}'", file.string(), field));
  }
  return j.at(field).get<double>();
}

}  // namespace

std::string readTextFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open file", path.string()));
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

CameraIntrinsics BopFrameCamera::intrinsics(int width, int height) const {
  CameraIntrinsics k;
  k.fx = K(0, 0);
  k.fy = K(1, 1);
  k.cx = K(0, 2);
  k.cy = K(1, 2);
  k.width = width;
  k.height = height;
  return k;
}

ObjectSymmetries BopObjectInfo::symmetries() const {
  ObjectSymmetries out;
  for (const Eigen::Matrix4d& m : symmetries_discrete) {
    Eigen::Isometry3f s = Eigen::Isometry3f::Identity();
    s.linear() = m.topLeftCorner<3, 3>().cast<float>();
    s.translation() = (m.topRightCorner<3, 1>() / 1000.0).cast<float>();
    out.discrete.push_back(s);
  }
  for (const ContinuousSymmetry& c : symmetries_continuous) {
    out.continuous.push_back(
        {c.axis.normalized().cast<float>(), (c.offset_mm / 1000.0).cast<float>()});
  }
  return out;
}

BopDataset::BopDataset(fs::path root, std::string split)
    : root_(std::move(root)), split_(std::move(split)) {
  std::error_code ec;
  if (!fs::is_directory(root_, ec)) {
    throw InputError(fmt::format("dataset {}: not a folder", root_.string()));
  }
  if (!fs::is_directory(root_ / split_, ec)) {
    throw InputError(fmt::format("dataset {}: no '{}' folder", root_.string(), split_));
  }
  if (!fs::is_directory(root_ / "models", ec)) {
    throw InputError(fmt::format("dataset {}: no 'models' folder", root_.string()));
  }
}

std::vector<int> BopDataset::sceneIds() const {
  std::vector<int> ids;
  for (const fs::directory_entry& e : fs::directory_iterator(root_ / split_)) {
    if (!e.is_directory()) continue;
    const std::string name = e.path().filename().string();
    if (name.size() == 6 && name.find_first_not_of("0123456789") == std::string::npos) {
      ids.push_back(std::stoi(name));
    }
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

fs::path BopDataset::sceneDir(int scene_id) const {
  return root_ / split_ / fmt::format("{:06d}", scene_id);
}

std::map<int, BopFrameCamera> BopDataset::sceneCameras(int scene_id) const {
  const fs::path file = sceneDir(scene_id) / "scene_camera.json";
  const json j = parseJsonFile(file);
  if (!j.is_object())
    throw InputError(fmt::format("{}: top level must be an object", file.string()));
  std::map<int, BopFrameCamera> cameras;
  for (const auto& [key, entry] : j.items()) {
    BopFrameCamera cam;
    const Eigen::Matrix<double, 9, 1> k = numbers<9>(file, entry, "cam_K");
    cam.K = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(k.data());
    cam.depth_scale = entry.contains("depth_scale") ? scalar(file, entry, "depth_scale") : 1.0;
    if (!(cam.K(0, 0) > 0) || !(cam.K(1, 1) > 0) || !(cam.depth_scale > 0)) {
      throw InputError(fmt::format("{}: image {} has a non-positive focal length or depth_scale",
                                   file.string(), key));
    }
    cameras[parseId(file, key)] = cam;
  }
  return cameras;
}

std::map<int, std::vector<BopGtInstance>> BopDataset::sceneGroundTruth(int scene_id) const {
  const fs::path file = sceneDir(scene_id) / "scene_gt.json";
  const json j = parseJsonFile(file);
  if (!j.is_object())
    throw InputError(fmt::format("{}: top level must be an object", file.string()));
  std::map<int, std::vector<BopGtInstance>> gt;
  for (const auto& [key, list] : j.items()) {
    if (!list.is_array())
      throw InputError(fmt::format("{}: image {} must hold a list", file.string(), key));
    std::vector<BopGtInstance>& instances = gt[parseId(file, key)];
    for (const json& entry : list) {
      BopGtInstance g;
      const Eigen::Matrix<double, 9, 1> r = numbers<9>(file, entry, "cam_R_m2c");
      g.R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(r.data());
      g.t_mm = numbers<3>(file, entry, "cam_t_m2c");
      if (!entry.contains("obj_id") || !entry["obj_id"].is_number_integer()) {
        throw InputError(
            fmt::format("{}: image {} has an entry without an integer obj_id", file.string(), key));
      }
      g.obj_id = entry["obj_id"].get<int>();
      instances.push_back(g);
    }
  }
  return gt;
}

std::map<int, BopObjectInfo> BopDataset::modelsInfo() const {
  return readModelsInfo(root_ / "models" / "models_info.json");
}

std::map<int, BopObjectInfo> readModelsInfo(const fs::path& file) {
  std::map<int, BopObjectInfo> info;
  std::error_code ec;
  if (!fs::exists(file, ec)) return info;
  const json j = parseJsonFile(file);
  if (!j.is_object())
    throw InputError(fmt::format("{}: top level must be an object", file.string()));
  for (const auto& [key, entry] : j.items()) {
    BopObjectInfo o;
    o.diameter_mm = scalar(file, entry, "diameter");
    if (entry.contains("symmetries_discrete")) {
      for (const json& m : entry["symmetries_discrete"]) {
        const Eigen::Matrix<double, 16, 1> v = numbers<16>(file, json{{"matrix", m}}, "matrix");
        o.symmetries_discrete.push_back(
            Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(v.data()));
      }
    }
    if (entry.contains("symmetries_continuous")) {
      for (const json& s : entry["symmetries_continuous"]) {
        ContinuousSymmetry c;
        c.axis = numbers<3>(file, s, "axis").normalized();
        c.offset_mm = numbers<3>(file, s, "offset");
        o.symmetries_continuous.push_back(c);
      }
    }
    info[parseId(file, key)] = o;
  }
  return info;
}

fs::path BopDataset::modelPath(int obj_id) const {
  return root_ / "models" / fmt::format("obj_{:06d}.ply", obj_id);
}
bool BopDataset::hasModel(int obj_id) const {
  std::error_code ec;
  return fs::exists(modelPath(obj_id), ec);
}
fs::path BopDataset::depthPath(int scene_id, int im_id) const {
  return sceneDir(scene_id) / "depth" / fmt::format("{:06d}.png", im_id);
}
fs::path BopDataset::rgbPath(int scene_id, int im_id) const {
  return sceneDir(scene_id) / "rgb" / fmt::format("{:06d}.png", im_id);
}
fs::path BopDataset::colourPath(int scene_id, int im_id) const {
  std::error_code ec;
  for (const char* extension : {".png", ".jpg"}) {
    fs::path file = rgbPath(scene_id, im_id).replace_extension(extension);
    if (fs::exists(file, ec)) return file;
  }
  return {};
}
fs::path BopDataset::probabilityPath(int scene_id, int im_id, int obj_id) const {
  return sceneDir(scene_id) / "prob" / fmt::format("{:06d}_{:06d}.png", im_id, obj_id);
}
fs::path BopDataset::maskVisibPath(int scene_id, int im_id, int gt_index) const {
  return sceneDir(scene_id) / "mask_visib" / fmt::format("{:06d}_{:06d}.png", im_id, gt_index);
}

fs::path BopDataset::boundaryPath(int scene_id, int im_id) const {
  return sceneDir(scene_id) / "edge" / fmt::format("{:06d}.png", im_id);
}

cv::Mat BopDataset::loadDepth(int scene_id, int im_id) const {
  const fs::path file = depthPath(scene_id, im_id);
  cv::Mat depth = cv::imread(file.string(), cv::IMREAD_ANYDEPTH | cv::IMREAD_GRAYSCALE);
  if (depth.empty())
    throw InputError(fmt::format("{}: missing or not a readable image", file.string()));
  if (depth.type() != CV_16UC1) {
    throw InputError(fmt::format("{}: depth must be a single-channel 16-bit PNG", file.string()));
  }
  return depth;
}

cv::Mat BopDataset::loadProbability(int scene_id, int im_id, int obj_id) const {
  const fs::path file = probabilityPath(scene_id, im_id, obj_id);
  const cv::Mat raw = cv::imread(file.string(), cv::IMREAD_UNCHANGED);
  if (raw.empty())
    throw InputError(fmt::format("{}: missing or not a readable image", file.string()));
  try {
    return toProbabilityImage(raw);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", file.string(), e.what()));
  }
}

cv::Mat BopDataset::loadBoundary(int scene_id, int im_id) const {
  const fs::path file = boundaryPath(scene_id, im_id);
  std::error_code ec;
  if (!fs::exists(file, ec)) return {};
  cv::Mat boundary = cv::imread(file.string(), cv::IMREAD_UNCHANGED);
  if (boundary.empty() || boundary.type() != CV_8UC1) {
    throw InputError(
        fmt::format("{}: boundary map must be a single-channel 8-bit PNG", file.string()));
  }
  return boundary;
}

cv::Mat BopDataset::loadColour(int scene_id, int im_id, cv::Size size) const {
  const fs::path file = colourPath(scene_id, im_id);
  if (file.empty()) return {};
  cv::Mat bgr = cv::imread(file.string(), cv::IMREAD_COLOR);
  if (bgr.empty()) throw InputError(fmt::format("{}: not a readable image", file.string()));
  if (bgr.size() != size) {
    throw InputError(fmt::format("{}: colour image is {}x{} but the depth image is {}x{}",
                                 file.string(), bgr.cols, bgr.rows, size.width, size.height));
  }
  return bgr;
}

}  // namespace stocs
