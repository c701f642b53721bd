#include "stocs/geometry/surface_sampling.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <numeric>
#include <unordered_map>

#include "stocs/geometry/voxel_key.h"

namespace stocs {

double meshArea(const MeshData& mesh) {
  double area = 0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3f& a = mesh.vertices[t[0]];
    area += 0.5 * (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).norm();
  }
  return area;
}

Colour interpolateColour(const MeshData& mesh, const Eigen::Vector3i& t, const Eigen::Vector3f& w) {
  Colour sum = Colour::Zero();
  float known = 0;
  for (int k = 0; k < 3; ++k) {
    const Colour c = toColour(mesh.colours[t[k]]);
    if (!isKnown(c)) continue;
    sum += w[k] * c;
    known += w[k];
  }
  return known >= 0.5f ? Colour(sum / known) : unknownColour();
}

OrientedPoints sampleMeshSurface(const MeshData& mesh, size_t count, Rng& rng) {
  OrientedPoints out;
  std::vector<double> cumulative;
  std::vector<size_t> faces;
  std::vector<Eigen::Vector3f> face_normals;
  double total = 0;
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Eigen::Vector3i& t = mesh.triangles[f];
    const Eigen::Vector3f& a = mesh.vertices[t[0]];
    const Eigen::Vector3f cross = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);
    const float twice_area = cross.norm();
    if (!(twice_area > 0)) continue;  // degenerate triangles carry no surface
    total += 0.5 * twice_area;
    cumulative.push_back(total);
    faces.push_back(f);
    face_normals.push_back(cross / twice_area);
  }
  if (faces.empty()) return out;
  out.points.reserve(count);
  out.normals.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    const double target = uniform01(rng) * total;
    const size_t k = std::min<size_t>(
        std::upper_bound(cumulative.begin(), cumulative.end(), target) - cumulative.begin(),
        faces.size() - 1);
    const Eigen::Vector3i& t = mesh.triangles[faces[k]];
    float r1 = uniform01(rng), r2 = uniform01(rng);
    if (r1 + r2 > 1) {  // fold the unit square onto the triangle
      r1 = 1 - r1;
      r2 = 1 - r2;
    }
    const Eigen::Vector3f& a = mesh.vertices[t[0]];
    out.points.push_back(a + r1 * (mesh.vertices[t[1]] - a) + r2 * (mesh.vertices[t[2]] - a));
    out.normals.push_back(face_normals[k]);
    if (mesh.hasColour()) {
      out.colours.push_back(interpolateColour(mesh, t, Eigen::Vector3f(1 - r1 - r2, r1, r2)));
    }
  }
  return out;
}

std::vector<size_t> poissonDiscSubset(const std::vector<Eigen::Vector3f>& points, float radius,
                                      Rng& rng) {
  std::vector<size_t> order(points.size());
  std::iota(order.begin(), order.end(), size_t{0});
  for (size_t i = order.size(); i > 1; --i) {  // Fisher-Yates with the portable generator
    std::swap(order[i - 1], order[uniformIndex(rng, static_cast<uint32_t>(i))]);
  }
  // Cells of side radius: a conflicting kept point lies in one of the 27 cells around a point.
  std::unordered_map<uint64_t, std::vector<size_t>> kept_by_cell;
  const float inv = 1.0f / radius, r2 = radius * radius;
  std::vector<size_t> kept;
  for (size_t i : order) {
    const Eigen::Vector3i c = voxelCell(points[i], inv);
    bool free = true;
    for (int dx = -1; dx <= 1 && free; ++dx) {
      for (int dy = -1; dy <= 1 && free; ++dy) {
        for (int dz = -1; dz <= 1 && free; ++dz) {
          auto it = kept_by_cell.find(packVoxelCell(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == kept_by_cell.end()) continue;
          for (size_t j : it->second) {
            if ((points[j] - points[i]).squaredNorm() < r2) {
              free = false;
              break;
            }
          }
        }
      }
    }
    if (!free) continue;
    kept.push_back(i);
    kept_by_cell[packVoxelCell(c)].push_back(i);
  }
  return kept;
}

}  // namespace stocs
