#include "stocs/geometry/rigid_fit.h"

#include <Eigen/Dense>

namespace stocs {
namespace {

/// Entry (i, j) of the adjugate of s: the cofactor of s(j, i), by the 3x3 rule of Sarrus.
double adjugateEntry(const Eigen::Matrix4d& s, int i, int j) {
  // The indices other than k, from a table: selecting them in loops cost more than the products.
  static constexpr int kOthers[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  const int* rows = kOthers[j];
  const int* cols = kOthers[i];
  const auto e = [&](int r, int c) { return s(rows[r], cols[c]); };
  const double det = e(0, 0) * (e(1, 1) * e(2, 2) - e(1, 2) * e(2, 1)) -
                     e(0, 1) * (e(1, 0) * e(2, 2) - e(1, 2) * e(2, 0)) +
                     e(0, 2) * (e(1, 0) * e(2, 1) - e(1, 1) * e(2, 0));
  return (i + j) % 2 ? -det : det;
}

/// Rotation that best maps the centred points `a` onto the centred points `b` (least squares),
/// by the quaternion characteristic polynomial (QCP; Theobald 2005, Liu et al. 2010): the optimal
/// quaternion is the eigenvector of Horn's 4x4 key matrix K for its largest eigenvalue, found by
/// Newton steps on det(lambda I - K) from above, then read off a column of adj(K - lambda I).
/// Written by hand because it is a fit per congruent set (tens of thousands per object): it gives
/// Eigen::umeyama's rotation to about 1e-8 without the general 3x3 SVD where umeyama spends most
/// of its time. For collinear points (a repeated eigenvalue) the column is some optimal
/// rotation about their line; nothing when no column stands out (coincident points).
std::optional<Eigen::Matrix3d> quaternionFit(const Eigen::Matrix<double, 3, 4>& a,
                                             const Eigen::Matrix<double, 3, 4>& b) {
  const Eigen::Matrix3d m = a * b.transpose();  // m(i, j) = sum over points of a_i b_j
  const double xx = m(0, 0), xy = m(0, 1), xz = m(0, 2), yx = m(1, 0), yy = m(1, 1), yz = m(1, 2),
               zx = m(2, 0), zy = m(2, 1), zz = m(2, 2);
  Eigen::Matrix4d k;
  k << xx + yy + zz, yz - zy, zx - xz, xy - yx,  //
      yz - zy, xx - yy - zz, xy + yx, zx + xz,   //
      zx - xz, xy + yx, -xx + yy - zz, yz + zy,  //
      xy - yx, zx + xz, yz + zy, -xx - yy + zz;
  // K is traceless, so det(lambda I - K) = lambda^4 + e2 lambda^2 - e3 lambda + det K with
  // e2 = -tr(K^2) / 2 and e3 = tr(K^3) / 3 (Newton's identities).
  const Eigen::Matrix4d k2 = k * k;
  const double e2 = -0.5 * k2.trace(), e3 = k2.cwiseProduct(k.transpose()).sum() / 3.0,
               e4 = k.determinant();
  // (|a|^2 + |b|^2) / 2 bounds the largest eigenvalue from above (the residual is
  // |a|^2 + |b|^2 - 2 lambda >= 0), and Newton from above a polynomial's largest real root
  // descends onto it monotonically.
  const double scale = 0.5 * (a.squaredNorm() + b.squaredNorm());
  double lambda = scale;
  for (int it = 0; it < 50; ++it) {
    const double l2 = lambda * lambda;
    const double p = l2 * l2 + e2 * l2 - e3 * lambda + e4;
    const double dp = 4 * l2 * lambda + 2 * e2 * lambda - e3;
    if (!(dp != 0)) break;
    const double step = p / dp;
    lambda -= step;
    if (std::abs(step) <= 1e-12 * scale) break;
  }
  // K - lambda I has rank 3 for a simple eigenvalue, and its adjugate is then c v v^T for the
  // eigenvector v: the longest column is the one with the largest diagonal entry, so 4 + 3
  // cofactors give it instead of all 16.
  const Eigen::Matrix4d s = k - lambda * Eigen::Matrix4d::Identity();
  int longest = 0;
  double diagonal[4];
  for (int j = 0; j < 4; ++j) {
    diagonal[j] = adjugateEntry(s, j, j);
    if (std::abs(diagonal[j]) > std::abs(diagonal[longest])) longest = j;
  }
  Eigen::Vector4d best;
  for (int i = 0; i < 4; ++i) {
    best(i) = i == longest ? diagonal[i] : adjugateEntry(s, i, longest);
  }
  // Cofactors scale with the cube of the key matrix's entries; relative to that they vanish only
  // when the points (nearly) coincide.
  if (!(best.norm() > 1e-9 * scale * scale * scale)) return std::nullopt;
  best.normalize();
  return Eigen::Quaterniond(best(0), best(1), best(2), best(3)).toRotationMatrix();
}

}  // namespace

std::optional<Eigen::Isometry3f> fitRigid(const std::array<Eigen::Vector3f, 4>& model,
                                          const std::array<Eigen::Vector3f, 4>& scene,
                                          float max_rms, float* rms) {
  // Double precision: centimetre-scale point sets lose digits in the float cross-covariance.
  Eigen::Matrix<double, 3, 4> src, dst;
  for (int k = 0; k < 4; ++k) {
    src.col(k) = model[k].cast<double>();
    dst.col(k) = scene[k].cast<double>();
  }
  const Eigen::Vector3d src_mean = src.rowwise().mean(), dst_mean = dst.rowwise().mean();
  const Eigen::Matrix<double, 3, 4> a = src.colwise() - src_mean, b = dst.colwise() - dst_mean;
  Eigen::Matrix3d r;
  if (const std::optional<Eigen::Matrix3d> q = quaternionFit(a, b)) {
    r = *q;
  } else {
    // Coincident points: any rotation fits alike; Umeyama picks one.
    r = Eigen::umeyama(src, dst, false).topLeftCorner<3, 3>();
  }
  if (!r.allFinite() || !src_mean.allFinite() || !dst_mean.allFinite()) return std::nullopt;
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.linear() = r.cast<float>();
  pose.translation() = (dst_mean - r * src_mean).cast<float>();
  float sum = 0;
  for (int k = 0; k < 4; ++k) sum += (pose * model[k] - scene[k]).squaredNorm();
  const float residual = std::sqrt(sum / 4);
  if (rms) *rms = residual;
  if (!(residual <= max_rms)) return std::nullopt;
  return pose;
}

}  // namespace stocs
