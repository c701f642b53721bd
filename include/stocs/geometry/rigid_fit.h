#pragma once
// Stage 3 of StoCS: the rigid transform that best aligns a congruent set to its base.

#include <Eigen/Geometry>
#include <array>
#include <optional>

namespace stocs {

/// Least-squares rigid transform (Kabsch/Umeyama, no scale, det R = +1) mapping `model` points onto
/// `scene` points, or nothing when the RMS residual exceeds `max_rms` (metres) or the points are
/// degenerate. `rms` receives the residual when given.
std::optional<Eigen::Isometry3f> fitRigid(const std::array<Eigen::Vector3f, 4>& model,
                                          const std::array<Eigen::Vector3f, 4>& scene,
                                          float max_rms, float* rms = nullptr);

}  // namespace stocs
