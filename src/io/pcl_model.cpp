// PLY and PCD parsing is PCL's; this file only checks what PCL gives back. With
// pcd_scene_dataset.cpp it is the only core file that includes PCL headers, which are slow to
// compile.
#include "pcl_model.h"

#include <fmt/format.h>
#include <pcl/PolygonMesh.h>
#include <pcl/common/io.h>
#include <pcl/console/print.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_types.h>

#include <algorithm>

#include "model_file_check.h"
#include "stocs/util/error.h"

namespace stocs::detail {
namespace {

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

pcl::PolygonMesh readWithPcl(const std::string& path, const std::string& ext) {
  pcl::PolygonMesh mesh;
  QuietPcl quiet;
  int rc = -1;
  if (ext == ".ply") {
    checkPlyHeader(path);
    rc = pcl::io::loadPLYFile(path, mesh);
  } else {
    checkPcdHeader(path);
    rc = pcl::io::loadPCDFile(path, mesh.cloud);
  }
  if (rc < 0)
    throw InputError(fmt::format("model {}: not a readable {} file", path, ext.substr(1)));
  return mesh;
}

}  // namespace

MeshData readPclModel(const std::string& path, const std::string& ext) {
  const pcl::PolygonMesh mesh = readWithPcl(path, ext);
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
  for (const pcl::PointXYZ& p : xyz) out.vertices.push_back(p.getVector3fMap());
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
  return out;
}

}  // namespace stocs::detail
