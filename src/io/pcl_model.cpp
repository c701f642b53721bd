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
#include <cstring>

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

/// The field named `name`, or null.
const pcl::PCLPointField* findField(const pcl::PCLPointCloud2& cloud, const std::string& name) {
  const auto it = std::find_if(cloud.fields.begin(), cloud.fields.end(),
                               [&](const pcl::PCLPointField& f) { return f.name == name; });
  return it == cloud.fields.end() ? nullptr : &*it;
}

/// Per-point RGBA from the packed `rgba` field (alpha as stored) or `rgb` field (alpha 255), as
/// PCL reads a PLY's red, green, blue (and alpha) properties and a PCD's rgb(a) field; empty when
/// the cloud has neither.
std::vector<Rgba> packedColours(const std::string& path, const pcl::PCLPointCloud2& cloud) {
  const pcl::PCLPointField* rgba = findField(cloud, "rgba");
  const pcl::PCLPointField* field = rgba ? rgba : findField(cloud, "rgb");
  if (!field) return {};
  const uint64_t rows = cloud.height, cols = cloud.width;
  if (pcl::getFieldSize(field->datatype) != 4 || field->count > 1 ||
      uint64_t{field->offset} + 4 > cloud.point_step || cloud.data.size() < rows * cloud.row_step ||
      cloud.row_step < cols * cloud.point_step) {
    throw InputError(
        fmt::format("model {}: colour field '{}' is not 4 bytes per point", path, field->name));
  }
  std::vector<Rgba> colours;
  colours.reserve(rows * cols);
  for (uint64_t r = 0; r < rows; ++r) {
    for (uint64_t c = 0; c < cols; ++c) {
      uint32_t v = 0;  // 0xAARRGGBB, as PCL packs it
      std::memcpy(&v, &cloud.data[r * cloud.row_step + c * cloud.point_step + field->offset], 4);
      colours.emplace_back(v >> 16 & 0xff, v >> 8 & 0xff, v & 0xff, rgba ? v >> 24 : 0xff);
    }
  }
  return colours;
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
  out.colours = packedColours(path, mesh.cloud);
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
