#include "stocs_ros/stocs_node/output_frame.h"

#include <fmt/format.h>
#include <tf2_eigen/tf2_eigen.h>

#include "stocs/util/error.h"

namespace stocs_ros {
namespace {

/// The covariance of a pose error (x, y, z, then rotation about x, y, z) in a frame rotated by
/// `rotation`: both blocks turn with it.
Eigen::Matrix<double, 6, 6> rotateCovariance(const Eigen::Matrix<double, 6, 6>& covariance,
                                             const Eigen::Matrix3d& rotation) {
  Eigen::Matrix<double, 6, 6> r = Eigen::Matrix<double, 6, 6>::Zero();
  r.topLeftCorner<3, 3>() = rotation;
  r.bottomRightCorner<3, 3>() = rotation;
  return r * covariance * r.transpose();
}

}  // namespace

void moveResult(FrameResult& result, const Eigen::Isometry3d& output_from_input,
                const std::string& frame) {
  const Eigen::Isometry3f move = output_from_input.cast<float>();
  const Eigen::Matrix3d rotation = output_from_input.rotation();
  for (ObjectOutcome& o : result.objects) {
    for (stocs::InstancePose& instance : o.estimate.instances) {
      instance.pose = move * instance.pose;
      instance.covariance = rotateCovariance(instance.covariance, rotation);
    }
  }
  result.header.frame_id = frame;
}

OutputFrame::OutputFrame() : listener_(buffer_) {}

void OutputFrame::express(FrameResult& result, const std::string& frame, double timeout) {
  if (frame.empty() || frame == result.header.frame_id) return;
  geometry_msgs::TransformStamped transform;
  try {
    transform = buffer_.lookupTransform(frame, result.header.frame_id, result.header.stamp,
                                        ros::Duration(timeout));
  } catch (const tf2::TransformException& e) {
    throw stocs::InputError(fmt::format(
        "output frame: no transform from '{}' to '{}' at {:.3f} within {} s ({}); the frame's "
        "poses are not published",
        result.header.frame_id, frame, result.header.stamp.toSec(), timeout, e.what()));
  }
  moveResult(result, tf2::transformToEigen(transform), frame);
}

}  // namespace stocs_ros
