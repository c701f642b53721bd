#include "stocs/estimation/stages/least_constrained_slide.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>

namespace stocs {

Eigen::Isometry3f slideAlongLeastConstrained(const ObjectModel& model,
                                             const Eigen::Isometry3f& pose,
                                             const PoseCovariance& covariance,
                                             const LcpScorer& scorer,
                                             const FreeSpaceCheck& surface) {
  const auto ranking = [&](const Eigen::Isometry3f& p) {
    return scorer.detail(model, p, -1).score * (1 - surface.violation(model, p));
  };
  // The information of pure translations (the rotation held, as the slide holds it): its block
  // of the inverse covariance, whatever point the rotation is about. Eigenvalues come in
  // increasing order: the first vector is the least constrained translation.
  const Eigen::Matrix3d information = covariance.inverse().topLeftCorner<3, 3>();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> translation(information);
  const float step_length = kSlideStep * model.diameter;
  if (1 / std::sqrt(translation.eigenvalues()(0)) < kSlideLoose * step_length) return pose;
  const Eigen::Vector3f step = translation.eigenvectors().col(0).cast<float>() * step_length;
  const auto moved = [&](int k) {
    Eigen::Isometry3f out = pose;
    out.pretranslate(step * static_cast<float>(k));
    return out;
  };
  // A climb: step one way while each step ranks higher; if the first step did not, the other way.
  int at = 0;
  float best = ranking(pose);
  for (const int way : {1, -1}) {
    for (int k = way; std::abs(k) <= kSlideSteps; k += way) {
      const float r = ranking(moved(k));
      if (r <= kSlideGain * best) break;
      at = k;
      best = r;
    }
    if (at != 0) break;
  }
  return moved(at);
}

}  // namespace stocs
