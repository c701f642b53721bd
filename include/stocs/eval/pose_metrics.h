#pragma once
// Pose error metrics on model points (units are those of the points and translations).
//   ADD:   mean distance between corresponding model points under the two poses.
//   ADD-S: mean distance from each point under the estimate to the closest point under the truth,
//          which forgives any symmetry of the shape.
//   MSSD:  BOP's maximum symmetry-aware surface distance: the largest distance between
//          corresponding points, for the symmetric ground-truth pose that makes it smallest.

#include <Eigen/Geometry>
#include <limits>
#include <memory>
#include <vector>

namespace stocs {

struct RigidPose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
};

double addError(const std::vector<Eigen::Vector3f>& model_points, const RigidPose& estimate,
                const RigidPose& truth);

double addsError(const std::vector<Eigen::Vector3f>& model_points, const RigidPose& estimate,
                 const RigidPose& truth);

/// MSSD: min over `symmetries` S (model frame; include the identity) of max over the points x of
/// |(R_e x + t_e) - (R_g S_R x + R_g S_t + t_g)|, as the BOP toolkit defines it. +infinity without
/// symmetries; 0 for an empty model.
double mssdError(const std::vector<Eigen::Vector3f>& model_points, const RigidPose& estimate,
                 const RigidPose& truth, const std::vector<RigidPose>& symmetries);

/// ADD-S of many poses of one model. The kd-tree over the model points is built once: the closest
/// point is searched in the model frame of the truth, where the truth's points are the model's.
class AddsMetric {
 public:
  explicit AddsMetric(std::vector<Eigen::Vector3f> model_points);
  AddsMetric(AddsMetric&&) noexcept;
  AddsMetric& operator=(AddsMetric&&) noexcept;
  ~AddsMetric();

  /// ADD-S of `estimate` against `truth` (0 for an empty model). Returns +infinity as soon as the
  /// mean is certain to exceed `give_up_above`, which makes finding the nearest of many instances
  /// cheap.
  double error(const RigidPose& estimate, const RigidPose& truth,
               double give_up_above = std::numeric_limits<double>::infinity()) const;

  const std::vector<Eigen::Vector3f>& points() const;

 private:
  struct Index;
  std::unique_ptr<Index> index_;
};

}  // namespace stocs
