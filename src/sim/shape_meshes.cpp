#include "stocs/sim/shape_meshes.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace stocs {

MeshData boxMesh(const Eigen::Vector3f& size) {
  MeshData m;
  const Eigen::Vector3f h = size / 2;
  for (int i = 0; i < 8; ++i) {
    m.vertices.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                            (i & 4) ? h.z() : -h.z());
  }
  // Each face as a quad of corner indices in counter-clockwise order seen from outside.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.emplace_back(q[0], q[1], q[2]);
    m.triangles.emplace_back(q[0], q[2], q[3]);
  }
  return m;
}

MeshData latheMesh(const std::vector<Eigen::Vector2f>& profile, int segments) {
  MeshData m;
  const int rings = static_cast<int>(profile.size());
  std::vector<int> first(rings);  // first vertex of each ring
  std::vector<bool> pole(rings);
  for (int r = 0; r < rings; ++r) {
    first[r] = static_cast<int>(m.vertices.size());
    pole[r] = profile[r].x() == 0 && (r == 0 || r == rings - 1);
    for (int s = 0; s < (pole[r] ? 1 : segments); ++s) {
      const float a = 2.0f * static_cast<float>(M_PI) * s / segments;
      m.vertices.emplace_back(profile[r].x() * std::cos(a), profile[r].x() * std::sin(a),
                              profile[r].y());
    }
  }
  const auto at = [&](int r, int s) { return first[r] + (pole[r] ? 0 : s % segments); };
  for (int r = 0; r + 1 < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      // The quad a b c d, less the triangle that a pole makes degenerate.
      const int a = at(r, s), b = at(r, s + 1), c = at(r + 1, s + 1), d = at(r + 1, s);
      if (!pole[r]) m.triangles.emplace_back(a, b, c);
      if (!pole[r + 1]) m.triangles.emplace_back(a, c, d);
    }
  }
  return m;
}

MeshData cylinderMesh(float radius, float height, int segments) {
  return latheMesh({{0, 0}, {radius, 0}, {radius, height}, {0, height}}, segments);
}

MeshData tubeArcMesh(float arc_radius, float tube_radius, float from, float to, int arc_segments,
                     int tube_segments) {
  MeshData m;
  for (int k = 0; k <= arc_segments; ++k) {
    const float theta = from + (to - from) * k / arc_segments;
    const Eigen::Vector3f radial(std::cos(theta), 0, std::sin(theta));
    for (int j = 0; j < tube_segments; ++j) {
      const float phi = 2.0f * static_cast<float>(M_PI) * j / tube_segments;
      m.vertices.push_back(arc_radius * radial +
                           tube_radius *
                               (std::cos(phi) * radial + std::sin(phi) * Eigen::Vector3f::UnitY()));
    }
  }
  const auto at = [&](int k, int j) { return k * tube_segments + j % tube_segments; };
  for (int k = 0; k < arc_segments; ++k) {
    for (int j = 0; j < tube_segments; ++j) {
      m.triangles.emplace_back(at(k, j), at(k, j + 1), at(k + 1, j + 1));
      m.triangles.emplace_back(at(k, j), at(k + 1, j + 1), at(k + 1, j));
    }
  }
  // Flat caps: fans around the centre-line end points, facing back along the arc at its start and
  // forward at its end.
  for (const int k : {0, arc_segments}) {
    const float theta = k == 0 ? from : to;
    const int centre = static_cast<int>(m.vertices.size());
    m.vertices.emplace_back(arc_radius * std::cos(theta), 0, arc_radius * std::sin(theta));
    for (int j = 0; j < tube_segments; ++j) {
      if (k == 0) {
        m.triangles.emplace_back(centre, at(k, j + 1), at(k, j));
      } else {
        m.triangles.emplace_back(centre, at(k, j), at(k, j + 1));
      }
    }
  }
  return m;
}

MeshData gridBoxMesh(const Eigen::Vector3f& size, float cell) {
  MeshData m;
  for (int axis = 0; axis < 3; ++axis) {
    for (const float side : {-1.0f, 1.0f}) {
      // The face's grid axes u and v, with u x v along the outward normal.
      int u = (axis + 1) % 3, v = (axis + 2) % 3;
      if (side < 0) std::swap(u, v);
      const int nu = std::max(1, static_cast<int>(std::lround(size[u] / cell)));
      const int nv = std::max(1, static_cast<int>(std::lround(size[v] / cell)));
      const int first = static_cast<int>(m.vertices.size());
      for (int j = 0; j <= nv; ++j) {
        for (int i = 0; i <= nu; ++i) {
          Eigen::Vector3f p;
          p[axis] = side * size[axis] / 2;
          p[u] = size[u] * (static_cast<float>(i) / nu - 0.5f);
          p[v] = size[v] * (static_cast<float>(j) / nv - 0.5f);
          m.vertices.push_back(p);
        }
      }
      for (int j = 0; j < nv; ++j) {
        for (int i = 0; i < nu; ++i) {
          const int a = first + j * (nu + 1) + i, b = a + 1, c = a + nu + 2, d = a + nu + 1;
          m.triangles.emplace_back(a, b, c);
          m.triangles.emplace_back(a, c, d);
        }
      }
    }
  }
  return m;
}

MeshData paintedMesh(const MeshData& mesh,
                     const std::function<VertexColour(const Eigen::Vector3f&)>& paint) {
  MeshData out;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const int first = static_cast<int>(out.vertices.size());
    Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
    for (int k = 0; k < 3; ++k) {
      out.vertices.push_back(mesh.vertices[t[k]]);
      centroid += mesh.vertices[t[k]] / 3;
    }
    out.colours.insert(out.colours.end(), 3, paint(centroid));
    out.triangles.emplace_back(first, first + 1, first + 2);
  }
  return out;
}

void appendMesh(MeshData& mesh, const MeshData& part, const Eigen::Isometry3f& pose) {
  const int offset = static_cast<int>(mesh.vertices.size());
  for (const Eigen::Vector3f& v : part.vertices) mesh.vertices.push_back(pose * v);
  for (const Eigen::Vector3i& t : part.triangles)
    mesh.triangles.push_back(t + Eigen::Vector3i::Constant(offset));
}

}  // namespace stocs
