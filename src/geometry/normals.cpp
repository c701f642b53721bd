#include "stocs/geometry/normals.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

#include "stocs/geometry/knn_index.h"

namespace stocs {

const ParamSet<OrganizedNormalParams>& OrganizedNormalParams::schema() {
  static const ParamSet<OrganizedNormalParams> schema =
      ParamSet<OrganizedNormalParams>()
          .add(&OrganizedNormalParams::radius, "radius", "m", ParamRange::aboveUpTo(0, 0.2),
               "neighbours farther than this from the centre pixel are ignored (grows to 2.5 pixel "
               "footprints far away)")
          .flag("--normal-radius")
          .add(&OrganizedNormalParams::samples_per_axis, "samples_per_axis", "",
               ParamRange::closed(3, 99), "window samples per image axis at most (a stride)")
          .add(&OrganizedNormalParams::min_neighbours, "min_neighbours", "",
               ParamRange::closed(3, 10000), "fewer valid neighbours give no normal");
  return schema;
}

void OrganizedNormalParams::validate() const {
  schema().validate(*this);
}
namespace {

const Eigen::Vector3f kNoNormal =
    Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());

/// Smallest-eigenvalue eigenvector of a covariance, or NaN if the points are (nearly) collinear
/// (second eigenvalue at most 1e-3 of the largest). Written out rather than Eigen's closed-form
/// SelfAdjointEigenSolver::computeDirect, which reaches all three eigenvalues through atan2, sin
/// and cos (libm calls) and builds all three eigenvectors, for one normal per segment point. Here
/// the smallest root of the characteristic cubic comes by Newton's method from 0, and the
/// eigenvector as the kernel of the shifted matrix (the cross product of two of its columns, chosen
/// as Eigen chooses them). Double precision keeps the kernel exact when the two smaller eigenvalues
/// nearly coincide; the normal is then any direction across the largest one.
Eigen::Vector3f planeNormal(const Eigen::Matrix3f& covariance) {
  const double trace = covariance.trace();
  if (!(trace > 0)) return kNoNormal;                           // no spread, or NaN
  const Eigen::Matrix3d a = covariance.cast<double>() / trace;  // eigenvalues sum to 1
  // det(lambda I - a) = lambda^3 - lambda^2 + c1 lambda - c0.
  const double c1 = a(0, 0) * a(1, 1) - a(0, 1) * a(0, 1) + a(0, 0) * a(2, 2) - a(0, 2) * a(0, 2) +
                    a(1, 1) * a(2, 2) - a(1, 2) * a(1, 2);
  const double c0 = a.determinant();
  // Below the smallest root the cubic is negative, rising and (below 1/3, which the smallest of
  // three eigenvalues summing to 1 never exceeds) concave: Newton's steps from 0 climb to the root
  // without overshooting it, in one or two steps when it lies well below the others.
  double smallest = 0;
  for (int k = 0; k < 100; ++k) {
    const double value = ((smallest - 1) * smallest + c1) * smallest - c0;
    const double slope = (3 * smallest - 2) * smallest + c1;
    if (!(slope > 0) || !(value < 0)) break;
    const double step = value / slope;
    smallest -= step;
    if (!(step < -1e-15)) break;
  }
  // The other two from the rest of the cubic: they sum to 1 - smallest, their product is c1 less
  // the smallest times that sum.
  const double rest = 1 - smallest, product = c1 - smallest * rest;
  const double spread = std::sqrt(std::max(0.0, rest * rest - 4 * product));
  if (!(rest - spread > 1e-3 * (rest + spread))) return kNoNormal;  // 2 lambda_1 vs 2 lambda_2
  const Eigen::Matrix3d shifted = a - smallest * Eigen::Matrix3d::Identity();
  Eigen::Index i0 = 0;
  shifted.diagonal().cwiseAbs().maxCoeff(&i0);
  const Eigen::Vector3d c = shifted.col(i0);
  const Eigen::Vector3d k0 = c.cross(shifted.col((i0 + 1) % 3));
  const Eigen::Vector3d k1 = c.cross(shifted.col((i0 + 2) % 3));
  const Eigen::Vector3d kernel = k0.squaredNorm() > k1.squaredNorm() ? k0 : k1;
  if (!(kernel.squaredNorm() > 0)) return kNoNormal;
  return kernel.normalized().cast<float>();
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
      // Centred on p for numerical accuracy. The radius test also turns away invalid pixels:
      // NaN fails it, and a pixel with no depth lies at the origin, farther from p than the
      // radius whenever p is not within the radius of the camera.
      const Eigen::Vector3f d = cloud.points[v * cloud.width + u] - p;
      if (!(d.squaredNorm() <= r2)) continue;
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

/// Neighbours searched for the nearest point elsewhere (medianSpacing).
constexpr int kSpacingNeighbours = 8;
/// Pixels across the object in a visibility z-buffer at most (2048^2 floats: 16 MB).
constexpr float kMaxZBufferSide = 2048;

float medianSpacing(const std::vector<Eigen::Vector3f>& points) {
  if (points.size() < 2) return 0;
  KnnIndex index(points);
  const size_t stride = std::max<size_t>(1, points.size() / 4000);
  std::vector<float> spacing;
  std::vector<size_t> nn;
  std::vector<float> d2;
  for (size_t i = 0; i < points.size(); i += stride) {
    // The nearest point elsewhere: a model file may repeat a point (a face's vertex written once
    // per face), and a spacing of 0 would make the visibility z-buffers unbounded.
    index.knn(points[i], kSpacingNeighbours, nn, d2);
    const auto other = std::find_if(d2.begin(), d2.end(), [](float d) { return d > 0; });
    if (other != d2.end()) spacing.push_back(std::sqrt(*other));
  }
  if (spacing.empty()) return 0;
  std::nth_element(spacing.begin(), spacing.begin() + spacing.size() / 2, spacing.end());
  return spacing[spacing.size() / 2];
}

namespace {

/// The z-buffers' pixel: a point's footprint, but at most kMaxZBufferSide pixels across the object.
float zbufferPixel(const std::vector<Eigen::Vector3f>& points,
                   const VisibilityOrientationParams& params) {
  const float spacing = params.splat_radius > 0 ? params.splat_radius : medianSpacing(points);
  Eigen::AlignedBox3f box;
  for (const Eigen::Vector3f& p : points) box.extend(p);
  return std::max({spacing, box.diagonal().norm() / kMaxZBufferSide, 1e-6f});
}

}  // namespace

int orientNormalsByVisibility(const std::vector<Eigen::Vector3f>& points,
                              std::vector<Eigen::Vector3f>& normals,
                              const VisibilityOrientationParams& params) {
  const size_t n = points.size();
  if (n == 0) return 0;
  const float pixel = zbufferPixel(points, params);
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
