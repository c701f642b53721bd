#include "stocs/rigid_fit.h"

#include <Eigen/Dense>

namespace stocs {

std::optional<Eigen::Isometry3f> fitRigid(const std::array<Eigen::Vector3f, 4>& model,
                                          const std::array<Eigen::Vector3f, 4>& scene,
                                          float max_rms, float* rms) {
  // Double precision: centimetre-scale point sets lose digits in the float cross-covariance.
  Eigen::Matrix<double, 3, 4> src, dst;
  for (int k = 0; k < 4; ++k) {
    src.col(k) = model[k].cast<double>();
    dst.col(k) = scene[k].cast<double>();
  }
  const Eigen::Matrix4d m = Eigen::umeyama(src, dst, false);
  if (!m.allFinite()) return std::nullopt;
  Eigen::Isometry3f pose(m.cast<float>());
  float sum = 0;
  for (int k = 0; k < 4; ++k) sum += (pose * model[k] - scene[k]).squaredNorm();
  const float r = std::sqrt(sum / 4);
  if (rms) *rms = r;
  if (!(r <= max_rms)) return std::nullopt;
  return pose;
}

}  // namespace stocs
