// Reading a model file by its extension (PLY and PCD through PCL, the other mesh formats through
// assimp, in a process of its own), then the checks every format shares: finite coordinates and a
// plausible size.
#include "stocs/io/mesh_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "assimp_model.h"
#include "child_reader.h"
#include "pcl_model.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

MeshData readModelFile(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".ply" || ext == ".pcd") return detail::readPclModel(path, ext);
  if (detail::isAssimpFormat(ext)) {
    // In a process of its own: assimp crashes on some malformed files (fuzz/known_crashes).
    return detail::readAssimpModelInChild(path, ext);
  }
  throw InputError(fmt::format(
      "model {}: unsupported extension '{}' (use .ply, .pcd, .obj, .stl, .dae, .gltf or .glb)",
      path, ext));
}

/// The unit a file whose model is `file_diameter` (in the file's units) across is most likely
/// in, as advice for the error of an implausible size; empty when no common unit fits.
std::string likelyUnitAdvice(double file_diameter) {
  struct Unit {
    const char* name;
    double metres;
  };
  // In the order CAD and datasets use them; the first that gives a typical graspable size wins.
  static const Unit kUnits[] = {{"mm", 0.001}, {"m", 1}, {"cm", 0.01}, {"inches", 0.0254}};
  for (const Unit& u : kUnits) {
    const double metres = file_diameter * u.metres;
    if (metres >= 0.02 && metres <= 2.0) {
      return fmt::format(": if the file is in {} use unit scale {} (diameter {:.3g} m)", u.name,
                         u.metres, metres);
    }
  }
  return "";
}

}  // namespace

bool isMeshOnlyFormat(const std::string& path) {
  return detail::isAssimpFormat(lowerExtension(path));
}

MeshData loadMesh(const std::string& path, float unit_scale) {
  namespace fs = std::filesystem;
  if (!(unit_scale > 0) || !std::isfinite(unit_scale)) {
    throw InputError(
        fmt::format("model {}: unit scale {} must be a positive number", path, unit_scale));
  }
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError(fmt::format("model {}: no such file", path));
  if (fs::file_size(path, ec) == 0) throw InputError(fmt::format("model {}: file is empty", path));

  MeshData out = readModelFile(path);
  if (out.vertices.empty()) throw InputError(fmt::format("model {}: no vertices", path));
  for (size_t i = 0; i < out.vertices.size(); ++i) {
    out.vertices[i] *= unit_scale;
    if (!out.vertices[i].allFinite()) {
      throw InputError(fmt::format("model {}: vertex {} has a non-finite coordinate", path, i));
    }
  }
  if (out.hasColour() && out.colours.size() != out.vertices.size()) {
    throw InputError(fmt::format("model {}: {} vertex colours for {} vertices", path,
                                 out.colours.size(), out.vertices.size()));
  }
  const float diameter = pointSetDiameter(out.vertices);
  if (diameter < 1e-3f || diameter > 10.0f) {
    throw InputError(fmt::format(
        "model {}: diameter {:.4g} m after unit scale {} is implausible for an object; is the unit "
        "scale right? (BOP models are in mm: use 0.001){}",
        path, diameter, unit_scale, likelyUnitAdvice(diameter / unit_scale)));
  }
  return out;
}

}  // namespace stocs
