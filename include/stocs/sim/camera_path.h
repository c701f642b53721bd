#pragma once
// A smooth camera path around a tabletop for generated sequences, as a wrist camera on a robot arm
// moves: distance, elevation and azimuth about the table follow sums of sinusoids, the camera
// always looks at a point near the table centre, and time is scaled so that neither the
// translation nor the rotation speed ever exceeds its limit.

#include <Eigen/Geometry>
#include <vector>

#include "stocs/sim/scene_layout.h"
#include "stocs/util/random.h"

namespace stocs {

struct CameraPathLimits {
  double rate_hz = 30;             ///< frames per second
  float translation_speed = 0.15;  ///< greatest speed of the camera centre, m/s
  float rotation_speed = 0.5;      ///< greatest angular speed of the camera, rad/s
};

/// `frames` camera poses (table frame to camera optical frame, as randomCameraPose) at
/// `limits.rate_hz`, within the layout's distance and elevation ranges. Consecutive poses differ by
/// at most translation_speed / rate_hz metres and rotation_speed / rate_hz radians, and the fastest
/// step comes within about 1% of one of the limits; either limit at 0 holds the camera still.
/// Phases and the start azimuth come from `rng`.
std::vector<Eigen::Isometry3f> smoothCameraPath(const SceneLayoutParams& layout, int frames,
                                                const CameraPathLimits& limits, Rng& rng);

/// The angle of the rotation between two poses, radians.
float rotationAngle(const Eigen::Isometry3f& a, const Eigen::Isometry3f& b);

}  // namespace stocs
