// PLY and PCD parsing is PCL's; this file only checks what PCL gives back. With
// pcd_scene_dataset.cpp it is the only core file that includes PCL headers, which are slow to
// compile.
#include <fmt/format.h>
#include <pcl/PolygonMesh.h>
#include <pcl/common/io.h>
#include <pcl/console/print.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "model_file_check.h"
#include "stocs/io/mesh_io.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

bool hasField(const pcl::PCLPointCloud2& cloud, const std::string& name) {
  return std::any_of(cloud.fields.begin(), cloud.fields.end(),
                     [&](const pcl::PCLPointField& f) { return f.name == name; });
}

/// PCL reports problems on the console; the core reports them as exceptions instead.
class QuietPcl {
 public:
  QuietPcl() : saved_(pcl::console::getVerbosityLevel()) {
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  }
  ~QuietPcl() { pcl::console::setVerbosityLevel(saved_); }

 private:
  pcl::console::VERBOSITY_LEVEL saved_;
};

}  // namespace

MeshData loadMesh(const std::string& path, float unit_scale) {
  namespace fs = std::filesystem;
  if (!(unit_scale > 0) || !std::isfinite(unit_scale)) {
    throw InputError(
        fmt::format("model {}: unit scale {} must be a positive number", path, unit_scale));
  }
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError(fmt::format("model {}: no such file", path));
  if (fs::file_size(path, ec) == 0) throw InputError(fmt::format("model {}: file is empty", path));

  const std::string ext = lowerExtension(path);
  pcl::PolygonMesh mesh;
  {
    QuietPcl quiet;
    int rc = -1;
    if (ext == ".ply") {
      detail::checkPlyHeader(path);
      rc = pcl::io::loadPLYFile(path, mesh);
    } else if (ext == ".pcd") {
      detail::checkPcdHeader(path);
      rc = pcl::io::loadPCDFile(path, mesh.cloud);
    } else {
      throw InputError(
          fmt::format("model {}: unsupported extension '{}' (use .ply or .pcd)", path, ext));
    }
    if (rc < 0)
      throw InputError(fmt::format("model {}: not a readable {} file", path, ext.substr(1)));
  }
  if (!hasField(mesh.cloud, "x") || !hasField(mesh.cloud, "y") || !hasField(mesh.cloud, "z")) {
    throw InputError(fmt::format("model {}: vertices lack x, y or z", path));
  }
  // Checked before conversion: PCL's conversion misbehaves on an empty cloud.
  if (static_cast<uint64_t>(mesh.cloud.width) * mesh.cloud.height == 0 || mesh.cloud.data.empty()) {
    throw InputError(fmt::format("model {}: no vertices", path));
  }
  pcl::PointCloud<pcl::PointXYZ> xyz;
  pcl::fromPCLPointCloud2(mesh.cloud, xyz);

  MeshData out;
  out.vertices.reserve(xyz.size());
  for (size_t i = 0; i < xyz.size(); ++i) {
    const Eigen::Vector3f p = xyz[i].getVector3fMap() * unit_scale;
    if (!p.allFinite()) {
      throw InputError(fmt::format("model {}: vertex {} has a non-finite coordinate", path, i));
    }
    out.vertices.push_back(p);
  }
  const int nv = static_cast<int>(out.vertices.size());
  for (size_t f = 0; f < mesh.polygons.size(); ++f) {
    const auto& idx = mesh.polygons[f].vertices;
    for (const auto i : idx) {
      if (i < 0 || i >= nv) {
        throw InputError(
            fmt::format("model {}: face {} refers to vertex {} of {}", path, f, i, nv));
      }
    }
    for (size_t k = 2; k < idx.size(); ++k) {
      out.triangles.emplace_back(static_cast<int>(idx[0]), static_cast<int>(idx[k - 1]),
                                 static_cast<int>(idx[k]));
    }
  }
  const float diameter = pointSetDiameter(out.vertices);
  if (diameter < 1e-3f || diameter > 10.0f) {
    throw InputError(fmt::format(
        "model {}: diameter {:.4g} m after unit scale {} is implausible for an object; is the unit "
        "scale right? (BOP models are in mm: use 0.001)",
        path, diameter, unit_scale));
  }
  return out;
}

}  // namespace stocs
