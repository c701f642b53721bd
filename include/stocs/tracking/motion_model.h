#pragma once
// A damped constant-velocity model of an object's pose in the camera frame: the velocity of the
// model's centre and the angular velocity about it, measured between the last two accepted poses.
// Moving the centre rather than the model origin keeps a rotation from swinging an off-centre
// origin's translation.

#include <Eigen/Geometry>

namespace stocs {

class ConstantVelocity {
 public:
  /// `centre`: the model point the motion is measured at (model frame, metres).
  explicit ConstantVelocity(const Eigen::Vector3f& centre = Eigen::Vector3f::Zero())
      : centre_(centre) {}

  /// The velocity that took `from` to `to` in `dt` seconds (none when dt is not positive).
  void update(const Eigen::Isometry3f& from, const Eigen::Isometry3f& to, double dt);
  /// Forgets the velocity: the next prediction is the last pose.
  void stop();

  /// `last` moved on by `damping` times the velocity for `dt` seconds.
  Eigen::Isometry3f predict(const Eigen::Isometry3f& last, double dt, float damping) const;

  const Eigen::Vector3f& linear() const { return linear_; }    ///< m/s, of the centre
  const Eigen::Vector3f& angular() const { return angular_; }  ///< rad/s, rotation vector

 private:
  Eigen::Vector3f centre_;
  Eigen::Vector3f linear_ = Eigen::Vector3f::Zero();
  Eigen::Vector3f angular_ = Eigen::Vector3f::Zero();
};

}  // namespace stocs
