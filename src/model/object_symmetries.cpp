#include "stocs/model/object_symmetries.h"

#include <cmath>

namespace stocs {
namespace {

float rotationAngle(const Eigen::Matrix3f& a, const Eigen::Matrix3f& b) {
  return Eigen::AngleAxisf(a.transpose() * b).angle();
}

/// pose * S(theta), S the rotation about the symmetry axis, with theta maximising
/// trace(R_ref^T R S): for M = R_ref^T R and K = [a]x that trace is
/// cos(theta) (tr M - a'Ma) + sin(theta) tr(MK) + a'Ma.
Eigen::Isometry3f bestRotationAbout(const Eigen::Isometry3f& pose, const Eigen::Matrix3f& reference,
                                    const SymmetryAxis& symmetry) {
  const Eigen::Vector3f a = symmetry.axis.normalized();
  const Eigen::Matrix3f m = reference.transpose() * pose.linear();
  Eigen::Matrix3f k;
  k << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  const float aligned = a.dot(m * a);
  const float theta = std::atan2((m * k).trace(), m.trace() - aligned);
  Eigen::Isometry3f s = Eigen::Isometry3f::Identity();
  s.linear() = Eigen::AngleAxisf(theta, a).toRotationMatrix();
  s.translation() = symmetry.offset - s.linear() * symmetry.offset;
  return pose * s;
}

}  // namespace

Eigen::Isometry3f nearestEquivalentPose(const Eigen::Isometry3f& pose,
                                        const Eigen::Isometry3f& reference,
                                        const ObjectSymmetries& symmetries) {
  std::vector<Eigen::Isometry3f> candidates{pose};
  for (const Eigen::Isometry3f& s : symmetries.discrete) candidates.push_back(pose * s);
  Eigen::Isometry3f best = pose;
  float best_angle = rotationAngle(pose.linear(), reference.linear());
  for (Eigen::Isometry3f candidate : candidates) {
    for (const SymmetryAxis& c : symmetries.continuous) {
      candidate = bestRotationAbout(candidate, reference.linear(), c);
    }
    const float angle = rotationAngle(candidate.linear(), reference.linear());
    if (angle < best_angle) {
      best = candidate;
      best_angle = angle;
    }
  }
  return best;
}

Eigen::Isometry3f canonicalPose(const Eigen::Isometry3f& pose, const ObjectSymmetries& symmetries) {
  return symmetries.empty()
             ? pose
             : nearestEquivalentPose(pose, Eigen::Isometry3f::Identity(), symmetries);
}

bool isSymmetry(const Eigen::Isometry3f& motion, const ObjectSymmetries& symmetries,
                const Eigen::Vector3f& centre, float angle, float distance) {
  if (symmetries.empty()) return false;
  const Eigen::Isometry3f equivalent =
      nearestEquivalentPose(motion, Eigen::Isometry3f::Identity(), symmetries);
  return rotationAngle(equivalent.linear(), Eigen::Matrix3f::Identity()) < angle &&
         (equivalent * centre - centre).norm() < distance;
}

}  // namespace stocs
