#pragma once
// A frame's result expressed in the configured output frame (output.frame, e.g. base_link; REP
// 105): every pose and its covariance moved through TF at the input's stamp, so that TF, ~poses,
// ~objects, ~pose/*, ~markers and ~estimate all speak of that frame. A missing transform is an
// error naming both frames, never a pose left in the input's frame under the output's name.

#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <Eigen/Geometry>
#include <string>

#include "stocs_ros/stocs_node/frame_estimation.h"

namespace stocs_ros {

/// Moves every pose of `result` (each estimate's pose and instances, model to the result's frame)
/// by `output_from_input`, rotates their covariances with it, and names `frame` in the header.
void moveResult(FrameResult& result, const Eigen::Isometry3d& output_from_input,
                const std::string& frame);

class OutputFrame {
 public:
  OutputFrame();

  /// Expresses `result` in `frame` (nothing to do when empty or already the result's), waiting at
  /// most `timeout` seconds for the transform at the result's stamp. Throws stocs::InputError
  /// "output frame: ..." naming both frames when TF has no such transform.
  void express(FrameResult& result, const std::string& frame, double timeout);

 private:
  tf2_ros::Buffer buffer_;
  tf2_ros::TransformListener listener_;
};

}  // namespace stocs_ros
