#include "stocs/estimation/stages/least_constrained_slide.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>

namespace stocs {

namespace {

/// The estimator's ranking of `pose`: its objective on `region` times the share of its visible
/// surface not in free space.
float ranking(const ObjectModel& model, const Eigen::Isometry3f& pose, const LcpScorer& scorer,
              const FreeSpaceCheck& surface, int region) {
  return scorer.detail(model, pose, region).score * (1 - surface.violation(model, pose));
}

Eigen::Isometry3f movedBy(const Eigen::Isometry3f& pose, const Eigen::Vector3f& step, int k) {
  Eigen::Isometry3f out = pose;
  out.pretranslate(step * static_cast<float>(k));
  return out;
}

}  // namespace

Eigen::Isometry3f bestAlong(const ObjectModel& model, const Eigen::Isometry3f& pose,
                            const Eigen::Vector3f& step, int steps, const LcpScorer& scorer,
                            const FreeSpaceCheck& surface, int region) {
  const float start = ranking(model, pose, scorer, surface, region);
  int at = 0;
  float best = kSlideGain * start;
  for (int k = -steps; k <= steps; ++k) {
    if (k == 0) continue;
    const float r = ranking(model, movedBy(pose, step, k), scorer, surface, region);
    if (r > best) {
      at = k;
      best = r;
    }
  }
  return movedBy(pose, step, at);
}

Eigen::Isometry3f slideAlongLeastConstrained(const ObjectModel& model,
                                             const Eigen::Isometry3f& pose,
                                             const PoseCovariance& covariance,
                                             const LcpScorer& scorer,
                                             const FreeSpaceCheck& surface) {
  // The information of pure translations (the rotation held, as the slide holds it): its block
  // of the inverse covariance, whatever point the rotation is about. Eigenvalues come in
  // increasing order: the first vector is the least constrained translation.
  const Eigen::Matrix3d information = covariance.inverse().topLeftCorner<3, 3>();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> translation(information);
  const float step_length = kSlideStep * model.diameter;
  if (1 / std::sqrt(translation.eigenvalues()(0)) < kSlideLoose * step_length) return pose;
  const Eigen::Vector3f step = translation.eigenvectors().col(0).cast<float>() * step_length;
  // A climb: step one way while each step ranks higher; if the first step did not, the other way.
  int at = 0;
  float best = ranking(model, pose, scorer, surface, -1);
  for (const int way : {1, -1}) {
    for (int k = way; std::abs(k) <= kSlideSteps; k += way) {
      const float r = ranking(model, movedBy(pose, step, k), scorer, surface, -1);
      if (r <= kSlideGain * best) break;
      at = k;
      best = r;
    }
    if (at != 0) break;
  }
  return movedBy(pose, step, at);
}

}  // namespace stocs
