#include "stocs/pose_metrics.h"

#include <cmath>

#include "knn_index.h"

namespace stocs {
namespace {

std::vector<Eigen::Vector3f> transformed(const std::vector<Eigen::Vector3f>& points,
                                         const RigidPose& pose) {
  std::vector<Eigen::Vector3f> out;
  out.reserve(points.size());
  for (const Eigen::Vector3f& p : points)
    out.push_back((pose.R * p.cast<double>() + pose.t).cast<float>());
  return out;
}

}  // namespace

double addError(const std::vector<Eigen::Vector3f>& model_points, const RigidPose& estimate,
                const RigidPose& truth) {
  if (model_points.empty()) return 0;
  double sum = 0;
  for (const Eigen::Vector3f& p : model_points) {
    const Eigen::Vector3d q = p.cast<double>();
    sum += ((estimate.R * q + estimate.t) - (truth.R * q + truth.t)).norm();
  }
  return sum / model_points.size();
}

double addsError(const std::vector<Eigen::Vector3f>& model_points, const RigidPose& estimate,
                 const RigidPose& truth) {
  if (model_points.empty()) return 0;
  const std::vector<Eigen::Vector3f> gt = transformed(model_points, truth);
  const KnnIndex index(gt);
  std::vector<size_t> nn;
  std::vector<float> d2;
  double sum = 0;
  for (const Eigen::Vector3f& p : transformed(model_points, estimate)) {
    index.knn(p, 1, nn, d2);
    sum += std::sqrt(static_cast<double>(d2[0]));
  }
  return sum / model_points.size();
}

}  // namespace stocs
