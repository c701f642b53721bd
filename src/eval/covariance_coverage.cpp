#include "stocs/eval/covariance_coverage.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "stocs/eval/symmetries.h"

namespace stocs {

PoseError poseError(const RigidPose& estimate, const RigidPose& truth) {
  const Eigen::AngleAxisd rotation(estimate.R * truth.R.transpose());
  PoseError error;
  error << (estimate.t - truth.t) / 1000.0, rotation.angle() * rotation.axis();
  return error;
}

double mahalanobisSquared(const PoseError& error, const PoseCovarianceMatrix& covariance) {
  const Eigen::LLT<PoseCovarianceMatrix> llt(covariance);
  if (llt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  return error.dot(llt.solve(error));
}

double nearestSymmetricMahalanobis(const RigidPose& estimate, const RigidPose& truth,
                                   const std::vector<RigidPose>& symmetries,
                                   const PoseCovarianceMatrix& covariance) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const RigidPose& s : symmetries) {
    const RigidPose equivalent{truth.R * s.R, truth.R * s.t + truth.t};
    nearest = std::min(nearest, mahalanobisSquared(poseError(estimate, equivalent), covariance));
  }
  return nearest;
}

double chiSquare6Cdf(double x) {
  if (!(x > 0)) return 0;
  return 1 - std::exp(-x / 2) * (1 + x / 2 + x * x / 8);
}

EllipsoidCoverage ellipsoidCoverage(const std::vector<double>& squared_distances) {
  EllipsoidCoverage coverage;
  coverage.poses = static_cast<int>(squared_distances.size());
  if (squared_distances.empty()) return coverage;
  for (double d2 : squared_distances) {
    const double level = chiSquare6Cdf(d2);
    coverage.within50 += level <= 0.5;
    coverage.within90 += level <= 0.9;
  }
  coverage.within50 /= coverage.poses;
  coverage.within90 /= coverage.poses;
  return coverage;
}

EllipsoidCoverage correctPoseCoverage(const std::vector<TargetResult>& targets,
                                      const std::map<Target, PoseCovarianceMatrix>& covariances,
                                      const std::map<int, BopObjectInfo>& info) {
  std::map<int, std::vector<RigidPose>> symmetries;
  std::vector<double> distances;
  for (const TargetResult& t : targets) {
    const auto covariance = covariances.find(t.target);
    if (!t.errors.found || !t.errors.addsSuccess() || covariance == covariances.end() ||
        covariance->second.isZero()) {
      continue;
    }
    auto group = symmetries.find(t.target.obj_id);
    if (group == symmetries.end()) {
      const auto object = info.find(t.target.obj_id);
      group = symmetries
                  .emplace(t.target.obj_id, object == info.end()
                                                ? std::vector<RigidPose>{RigidPose{}}
                                                : symmetryTransformations(object->second))
                  .first;
    }
    distances.push_back(
        nearestSymmetricMahalanobis(t.estimate, t.truth, group->second, covariance->second));
  }
  return ellipsoidCoverage(distances);
}

}  // namespace stocs
