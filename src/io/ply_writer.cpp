#include "stocs/io/ply_writer.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>

#include "stocs/util/error.h"

namespace stocs {

void writePly(const std::filesystem::path& file, const MeshData& mesh, float scale, int decimals) {
  std::string text = fmt::format(
      "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\nproperty "
      "float z\n",
      mesh.vertices.size());
  if (mesh.hasColour()) {
    if (mesh.colours.size() != mesh.vertices.size()) {
      throw InputError(fmt::format("{}: {} vertex colours for {} vertices", file.string(),
                                   mesh.colours.size(), mesh.vertices.size()));
    }
    text += "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n";
  }
  if (mesh.isMesh()) {
    text += fmt::format("element face {}\nproperty list uchar int vertex_indices\n",
                        mesh.triangles.size());
  }
  text += "end_header\n";
  const double step = std::pow(10.0, decimals);
  const auto number = [&](float value) {
    double v = std::round(static_cast<double>(value) * scale * step) / step;
    if (v == 0) v = 0;  // never print "-0"
    return fmt::format("{:.{}f}", v, decimals);
  };
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3f& v = mesh.vertices[i];
    text += number(v.x()) + ' ' + number(v.y()) + ' ' + number(v.z());
    if (mesh.hasColour()) {
      const Eigen::Vector4i c = mesh.colours[i].cast<int>();  // numbers, not characters
      text += fmt::format(" {} {} {} {}", c[0], c[1], c[2], c[3]);
    }
    text += '\n';
  }
  for (const Eigen::Vector3i& t : mesh.triangles)
    text += fmt::format("3 {} {} {}\n", t[0], t[1], t[2]);
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw InputError(fmt::format("{}: cannot write file", file.string()));
}

}  // namespace stocs
