#include "stocs/sim/bop_writer.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "stocs/io/ply_writer.h"
#include "stocs/util/error.h"

namespace stocs {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

/// Millimetres rounded to 0.1 um, so that the text does not carry float noise.
double roundMm(double mm) {
  const double r = std::round(mm * 1e4) / 1e4;
  return r == 0 ? 0.0 : r;
}

/// One top-level entry per line: short enough to read, diff and review.
void writeJson(const fs::path& file, const json& j) {
  std::string text = "{";
  for (auto it = j.begin(); it != j.end(); ++it) {
    text += fmt::format("{}\n \"{}\": {}", it == j.begin() ? "" : ",", it.key(), it.value().dump());
  }
  text += "\n}\n";
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw InputError(fmt::format("{}: cannot write file", file.string()));
}

template <class Matrix>
json rowMajor(const Matrix& m) {
  json a = json::array();
  for (int r = 0; r < m.rows(); ++r) {
    for (int c = 0; c < m.cols(); ++c) a.push_back(m(r, c));
  }
  return a;
}

/// One entry per image id: the list of its instances, each as `entry` writes it.
template <class Instance, class Entry>
json perImage(const std::map<int, std::vector<Instance>>& by_image, const Entry& entry) {
  json j = json::object();
  for (const auto& [im, instances] : by_image) {
    json list = json::array();
    for (const Instance& instance : instances) list.push_back(entry(instance));
    j[std::to_string(im)] = list;
  }
  return j;
}

/// `o`'s mesh as its model file holds it: its own colours, or its plain colour at every vertex.
MeshData colouredMesh(const CatalogueObject& o) {
  MeshData mesh = o.mesh;
  if (!mesh.hasColour()) mesh.colours.assign(mesh.vertices.size(), plainColour(o.id));
  return mesh;
}

}  // namespace

void writeModels(const fs::path& models_dir, const std::vector<CatalogueObject>& objects) {
  json info = json::object();
  for (const CatalogueObject& o : objects) {
    writePly(models_dir / fmt::format("obj_{:06d}.ply", o.id), colouredMesh(o), 1000.0f, 4);
    Eigen::Vector3f lo = o.mesh.vertices.front(), hi = lo;
    for (const Eigen::Vector3f& v : o.mesh.vertices) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
    json entry = {{"diameter", roundMm(pointSetDiameter(o.mesh.vertices) * 1000.0)}};
    const char* axes[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
      entry[std::string("min_") + axes[k]] = roundMm(lo[k] * 1000.0);
      entry[std::string("size_") + axes[k]] = roundMm((hi[k] - lo[k]) * 1000.0);
    }
    if (!o.symmetries.symmetries_discrete.empty()) {
      entry["symmetries_discrete"] = json::array();
      for (const Eigen::Matrix4d& m : o.symmetries.symmetries_discrete) {
        entry["symmetries_discrete"].push_back(rowMajor(m));
      }
    }
    if (!o.symmetries.symmetries_continuous.empty()) {
      entry["symmetries_continuous"] = json::array();
      for (const ContinuousSymmetry& s : o.symmetries.symmetries_continuous) {
        entry["symmetries_continuous"].push_back(
            {{"axis", rowMajor(s.axis)}, {"offset", rowMajor(s.offset_mm)}});
      }
    }
    info[std::to_string(o.id)] = entry;
  }
  writeJson(models_dir / "models_info.json", info);
}

void writeSceneCameras(const fs::path& file, const std::map<int, BopFrameCamera>& cameras) {
  json j = json::object();
  for (const auto& [im, camera] : cameras) {
    j[std::to_string(im)] = {{"cam_K", rowMajor(camera.K)}, {"depth_scale", camera.depth_scale}};
  }
  writeJson(file, j);
}

void writeSceneGroundTruth(const fs::path& file,
                           const std::map<int, std::vector<BopGtInstance>>& gt) {
  writeJson(file, perImage(gt, [](const BopGtInstance& g) {
              return json{{"cam_R_m2c", rowMajor(g.R)},
                          {"cam_t_m2c", rowMajor(g.t_mm)},
                          {"obj_id", g.obj_id}};
            }));
}

void writeSceneGtInfo(const fs::path& file, const std::map<int, std::vector<BopGtInfo>>& info) {
  writeJson(file, perImage(info, [](const BopGtInfo& g) {
              return json{{"px_count_all", g.px_count_all},
                          {"px_count_visib", g.px_count_visib},
                          {"visib_fract", g.visib_fract},
                          {"bbox_visib",
                           {g.bbox_visib[0], g.bbox_visib[1], g.bbox_visib[2], g.bbox_visib[3]}}};
            }));
}

void writeSceneHandles(const fs::path& file,
                       const std::map<int, std::vector<HandleVisibility>>& handles) {
  writeJson(file, perImage(handles, [](const HandleVisibility& h) {
              return json{{"gt_index", h.gt_index},
                          {"obj_id", h.obj_id},
                          {"px_count_all", h.px_count_all},
                          {"px_count_visib", h.px_count_visib},
                          {"handle_visible", h.visible()}};
            }));
}

}  // namespace stocs
