#include "stocs/normals.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

#include "knn_index.h"

namespace stocs {
namespace {

const Eigen::Vector3f kNoNormal =
    Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());

/// Smallest-eigenvalue eigenvector of a covariance, or NaN if the points are (nearly) collinear.
Eigen::Vector3f planeNormal(const Eigen::Matrix3f& covariance) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> solver;
  solver.computeDirect(covariance);
  const Eigen::Vector3f ev = solver.eigenvalues();  // ascending
  if (!(ev[1] > 1e-3f * ev[2])) return kNoNormal;
  return solver.eigenvectors().col(0).normalized();
}

/// Points on a sphere, evenly spread (Fibonacci lattice).
std::vector<Eigen::Vector3f> sphereDirections(int n) {
  std::vector<Eigen::Vector3f> dirs(n);
  const float golden = static_cast<float>(M_PI * (3.0 - std::sqrt(5.0)));
  for (int i = 0; i < n; ++i) {
    const float z = 1.0f - 2.0f * (i + 0.5f) / n;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    dirs[i] = Eigen::Vector3f(r * std::cos(golden * i), r * std::sin(golden * i), z);
  }
  return dirs;
}

}  // namespace

Eigen::Vector3f organizedNormal(const OrganizedCloud& cloud, int index, float focal_px,
                                const OrganizedNormalParams& params) {
  if (!cloud.isValid(index)) return kNoNormal;
  const Eigen::Vector3f& p = cloud.points[index];
  const int u0 = index % cloud.width, v0 = index / cloud.width;
  const float radius = std::max(params.radius, 2.5f * p.z() / focal_px);
  const int reach = std::max(1, static_cast<int>(std::ceil(radius * focal_px / p.z())));
  // Rounded up, so that a window holds at most samples_per_axis samples per axis (rounded down,
  // a reach of 7 pixels took 15 x 15 samples instead of 8 x 8).
  const int intervals = std::max(1, params.samples_per_axis - 1);
  const int step = std::max(1, (2 * reach + intervals - 1) / intervals);
  const float r2 = radius * radius;

  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  Eigen::Matrix3f outer = Eigen::Matrix3f::Zero();
  int n = 0;
  for (int v = std::max(0, v0 - reach); v <= std::min(cloud.height - 1, v0 + reach); v += step) {
    for (int u = std::max(0, u0 - reach); u <= std::min(cloud.width - 1, u0 + reach); u += step) {
      const int j = v * cloud.width + u;
      if (!cloud.isValid(j)) continue;
      const Eigen::Vector3f d = cloud.points[j] - p;  // centred on p for numerical accuracy
      if (d.squaredNorm() > r2) continue;
      sum += d;
      outer += d * d.transpose();
      ++n;
    }
  }
  if (n < params.min_neighbours) return kNoNormal;
  const Eigen::Vector3f mean = sum / n;
  Eigen::Vector3f normal = planeNormal(outer / n - mean * mean.transpose());
  if (!normal.allFinite()) return kNoNormal;
  if (normal.dot(p) > 0) normal = -normal;  // face the camera at the origin
  return normal;
}

std::vector<Eigen::Vector3f> estimatePcaNormals(const std::vector<Eigen::Vector3f>& points, int k) {
  std::vector<Eigen::Vector3f> normals(points.size(), kNoNormal);
  if (points.size() < 3) return normals;
  KnnIndex index(points);
  std::vector<size_t> nn;
  std::vector<float> d2;
  for (size_t i = 0; i < points.size(); ++i) {
    index.knn(points[i], static_cast<size_t>(std::max(3, k)), nn, d2);
    Eigen::Vector3f mean = Eigen::Vector3f::Zero();
    for (size_t j : nn) mean += points[j];
    mean /= static_cast<float>(nn.size());
    Eigen::Matrix3f cov = Eigen::Matrix3f::Zero();
    for (size_t j : nn) cov += (points[j] - mean) * (points[j] - mean).transpose();
    normals[i] = planeNormal(cov);
  }
  // A degenerate neighbourhood (collinear samples) borrows the nearest usable normal.
  for (size_t i = 0; i < points.size(); ++i) {
    if (normals[i].allFinite()) continue;
    index.knn(points[i], 32, nn, d2);
    for (size_t j : nn) {
      if (normals[j].allFinite()) {
        normals[i] = normals[j];
        break;
      }
    }
    if (!normals[i].allFinite()) normals[i] = Eigen::Vector3f::UnitZ();
  }
  return normals;
}

float medianSpacing(const std::vector<Eigen::Vector3f>& points) {
  if (points.size() < 2) return 0;
  KnnIndex index(points);
  const size_t stride = std::max<size_t>(1, points.size() / 4000);
  std::vector<float> spacing;
  std::vector<size_t> nn;
  std::vector<float> d2;
  for (size_t i = 0; i < points.size(); i += stride) {
    index.knn(points[i], 2, nn, d2);
    if (nn.size() == 2) spacing.push_back(std::sqrt(d2[1]));
  }
  std::nth_element(spacing.begin(), spacing.begin() + spacing.size() / 2, spacing.end());
  return spacing[spacing.size() / 2];
}

int orientNormalsByVisibility(const std::vector<Eigen::Vector3f>& points,
                              std::vector<Eigen::Vector3f>& normals,
                              const VisibilityOrientationParams& params) {
  const size_t n = points.size();
  if (n == 0) return 0;
  const float spacing = params.splat_radius > 0 ? params.splat_radius : medianSpacing(points);
  const float pixel = std::max(spacing, 1e-6f);
  const float tolerance = pixel;  // depth slack for a point to count as the visible surface

  // votes[i] > 0: the normal faces the viewpoints that see point i.
  std::vector<float> votes(n, 0.0f);
  std::vector<int> pu(n), pv(n);
  std::vector<float> depth(n);
  std::vector<float> zbuffer;
  for (const Eigen::Vector3f& view : sphereDirections(std::max(6, params.viewpoints))) {
    // Orthographic camera looking along -view; larger `depth` means nearer the viewer.
    const Eigen::Vector3f e1 = view.unitOrthogonal(), e2 = view.cross(e1);
    float umin = std::numeric_limits<float>::max(), vmin = umin;
    for (size_t i = 0; i < n; ++i) {
      umin = std::min(umin, points[i].dot(e1));
      vmin = std::min(vmin, points[i].dot(e2));
    }
    int width = 0, height = 0;
    for (size_t i = 0; i < n; ++i) {
      pu[i] = 1 + static_cast<int>((points[i].dot(e1) - umin) / pixel);
      pv[i] = 1 + static_cast<int>((points[i].dot(e2) - vmin) / pixel);
      depth[i] = points[i].dot(view);
      width = std::max(width, pu[i] + 2);
      height = std::max(height, pv[i] + 2);
    }
    zbuffer.assign(static_cast<size_t>(width) * height, -std::numeric_limits<float>::max());
    // Each point covers its pixel and the 8 around it, closing holes between samples.
    for (size_t i = 0; i < n; ++i) {
      for (int dv = -1; dv <= 1; ++dv) {
        for (int du = -1; du <= 1; ++du) {
          float& z = zbuffer[(pv[i] + dv) * width + pu[i] + du];
          z = std::max(z, depth[i]);
        }
      }
    }
    for (size_t i = 0; i < n; ++i) {
      if (depth[i] < zbuffer[pv[i] * width + pu[i]] - tolerance) continue;  // hidden
      votes[i] += normals[i].dot(view);  // grazing views weigh little
    }
  }

  // Orient voted points; propagate to unseen ones breadth-first from their nearest oriented
  // neighbours.
  int flipped = 0;
  std::vector<char> oriented(n, 0);
  std::deque<size_t> frontier;
  for (size_t i = 0; i < n; ++i) {
    if (votes[i] == 0.0f) continue;
    if (votes[i] < 0) {
      normals[i] = -normals[i];
      ++flipped;
    }
    oriented[i] = 1;
    frontier.push_back(i);
  }
  if (frontier.empty()) return flipped;
  KnnIndex index(points);
  std::vector<size_t> nn;
  std::vector<float> d2;
  while (!frontier.empty()) {
    const size_t i = frontier.front();
    frontier.pop_front();
    index.knn(points[i], 8, nn, d2);
    for (size_t j : nn) {
      if (oriented[j]) continue;
      if (normals[j].dot(normals[i]) < 0) {
        normals[j] = -normals[j];
        ++flipped;
      }
      oriented[j] = 1;
      frontier.push_back(j);
    }
  }
  return flipped;
}

}  // namespace stocs
