#include "stocs/tracking/motion_model.h"

namespace stocs {

void ConstantVelocity::update(const Eigen::Isometry3f& from, const Eigen::Isometry3f& to,
                              double dt) {
  if (!(dt > 0)) return stop();
  const auto seconds = static_cast<float>(dt);
  linear_ = (to * centre_ - from * centre_) / seconds;
  const Eigen::AngleAxisf turn(Eigen::Matrix3f(to.linear() * from.linear().transpose()));
  angular_ = turn.axis() * (turn.angle() / seconds);
}

void ConstantVelocity::stop() {
  linear_.setZero();
  angular_.setZero();
}

Eigen::Isometry3f ConstantVelocity::predict(const Eigen::Isometry3f& last, double dt,
                                            float damping) const {
  const float scale = damping * static_cast<float>(dt > 0 ? dt : 0);
  const Eigen::Vector3f rotation = angular_ * scale;
  const float angle = rotation.norm();
  Eigen::Isometry3f next = last;
  if (angle > 0) next.linear() = Eigen::AngleAxisf(angle, rotation / angle) * last.linear();
  // The centre moves on at its velocity; the origin follows it under the new rotation.
  const Eigen::Vector3f centre = last * centre_ + linear_ * scale;
  next.translation() = centre - next.linear() * centre_;
  return next;
}

}  // namespace stocs
