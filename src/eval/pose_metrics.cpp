#include "stocs/eval/pose_metrics.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "stocs/geometry/knn_index.h"

namespace stocs {

struct AddsMetric::Index {
  explicit Index(std::vector<Eigen::Vector3f> p) : points(std::move(p)) {
    if (!points.empty()) tree.emplace(points);
  }
  std::vector<Eigen::Vector3f> points;
  std::optional<KnnIndex>
      tree;  // refers to `points`, so an Index never moves (it is held by pointer)
};

AddsMetric::AddsMetric(std::vector<Eigen::Vector3f> model_points)
    : index_(std::make_unique<Index>(std::move(model_points))) {}
AddsMetric::AddsMetric(AddsMetric&&) noexcept = default;
AddsMetric& AddsMetric::operator=(AddsMetric&&) noexcept = default;
AddsMetric::~AddsMetric() = default;

const std::vector<Eigen::Vector3f>& AddsMetric::points() const {
  return index_->points;
}

double AddsMetric::error(const RigidPose& estimate, const RigidPose& truth,
                         double give_up_above) const {
  const std::vector<Eigen::Vector3f>& points = index_->points;
  if (points.empty()) return 0;
  // x -> truth^-1 * estimate * x maps the estimate's points into the truth's model frame.
  const Eigen::Matrix3d R = truth.R.transpose() * estimate.R;
  const Eigen::Vector3d t = truth.R.transpose() * (estimate.t - truth.t);
  const double give_up_sum = give_up_above * points.size();
  std::vector<size_t> nn;
  std::vector<float> d2;
  double sum = 0;
  for (const Eigen::Vector3f& p : points) {
    index_->tree->knn((R * p.cast<double>() + t).cast<float>(), 1, nn, d2);
    sum += std::sqrt(static_cast<double>(d2[0]));
    if (sum > give_up_sum) return std::numeric_limits<double>::infinity();
  }
  return sum / points.size();
}

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

double mssdError(const std::vector<Eigen::Vector3f>& model_points, const RigidPose& estimate,
                 const RigidPose& truth, const std::vector<RigidPose>& symmetries) {
  if (model_points.empty()) return 0;
  double best = std::numeric_limits<double>::infinity();
  for (const RigidPose& s : symmetries) {
    // x -> (truth S)^-1 estimate x: the distance of a point is the same in that model frame.
    const Eigen::Matrix3d R_truth = truth.R * s.R;
    const Eigen::Vector3d t_truth = truth.R * s.t + truth.t;
    const Eigen::Matrix3d R = R_truth.transpose() * estimate.R;
    const Eigen::Vector3d t = R_truth.transpose() * (estimate.t - t_truth);
    double worst = 0;
    for (const Eigen::Vector3f& p : model_points) {
      const Eigen::Vector3d q = p.cast<double>();
      worst = std::max(worst, (R * q + t - q).squaredNorm());
      if (worst >= best * best) break;  // this symmetry cannot beat the best
    }
    best = std::min(best, std::sqrt(worst));
  }
  return best;
}

double addsError(const std::vector<Eigen::Vector3f>& model_points, const RigidPose& estimate,
                 const RigidPose& truth) {
  return AddsMetric(model_points).error(estimate, truth);
}

}  // namespace stocs
