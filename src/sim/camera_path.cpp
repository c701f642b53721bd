#include "stocs/sim/camera_path.h"

#include <algorithm>
#include <cmath>

namespace stocs {
namespace {

constexpr float kPi = static_cast<float>(M_PI);

/// The path before its time is scaled: the camera pose at path time `tau` (dimensionless).
class RawPath {
 public:
  RawPath(const SceneLayoutParams& layout, Rng& rng) : layout_(layout) {
    start_azimuth_ = 2 * kPi * uniform01(rng);
    for (float& p : phase_) p = 2 * kPi * uniform01(rng);
  }

  Eigen::Isometry3f at(double tau) const {
    const float t = static_cast<float>(tau);
    const float mid_elevation = (layout_.min_elevation_deg + layout_.max_elevation_deg) / 2,
                half_elevation = (layout_.max_elevation_deg - layout_.min_elevation_deg) / 2;
    const float mid_distance = (layout_.min_distance + layout_.max_distance) / 2,
                half_distance = (layout_.max_distance - layout_.min_distance) / 2;
    // Going round the table with a swing, up and down, in and out: frequencies that share no
    // period, so the path does not repeat within a sequence. 0.8 keeps inside the ranges.
    const float azimuth = start_azimuth_ + 0.5f * t + 0.4f * std::sin(0.7f * t + phase_[0]);
    const float elevation =
        (mid_elevation + 0.8f * half_elevation * std::sin(0.9f * t + phase_[1])) * kPi / 180;
    const float distance = mid_distance + 0.8f * half_distance * std::sin(1.1f * t + phase_[2]);
    const Eigen::Vector3f target(0.03f * std::sin(1.3f * t + phase_[3]),
                                 0.03f * std::sin(0.8f * t + phase_[4]), 0.03f);
    const Eigen::Vector3f eye =
        target + distance * Eigen::Vector3f(std::cos(elevation) * std::cos(azimuth),
                                            std::cos(elevation) * std::sin(azimuth),
                                            std::sin(elevation));
    return cameraLookingAt(eye, target);
  }

 private:
  SceneLayoutParams layout_;
  float start_azimuth_ = 0;
  float phase_[5] = {};
};

/// The largest step between consecutive poses relative to the limits' step per frame (1: at the
/// limit); 0 for a still path.
double worstStepRatio(const std::vector<Eigen::Isometry3f>& poses, const CameraPathLimits& limits) {
  const double max_move = limits.translation_speed / limits.rate_hz,
               max_turn = limits.rotation_speed / limits.rate_hz;
  double worst = 0;
  for (size_t i = 1; i < poses.size(); ++i) {
    const double move =
        (poses[i].inverse().translation() - poses[i - 1].inverse().translation()).norm();
    const double turn = rotationAngle(poses[i], poses[i - 1]);
    worst = std::max({worst, move / max_move, turn / max_turn});
  }
  return worst;
}

std::vector<Eigen::Isometry3f> sample(const RawPath& path, int frames, double tau_per_frame) {
  std::vector<Eigen::Isometry3f> poses;
  for (int f = 0; f < frames; ++f) poses.push_back(path.at(f * tau_per_frame));
  return poses;
}

}  // namespace

float rotationAngle(const Eigen::Isometry3f& a, const Eigen::Isometry3f& b) {
  return Eigen::AngleAxisf(a.linear().transpose() * b.linear()).angle();
}

std::vector<Eigen::Isometry3f> smoothCameraPath(const SceneLayoutParams& layout, int frames,
                                                const CameraPathLimits& limits, Rng& rng) {
  const RawPath path(layout, rng);
  if (!(limits.translation_speed > 0 && limits.rotation_speed > 0)) return sample(path, frames, 0);
  // The raw path's speeds per unit of path time on a fine grid give a first time scale; the
  // steps between the frames themselves then set it, so that the fastest step is at the limit.
  constexpr double kStep = 0.01;
  const CameraPathLimits per_step{1 / kStep, limits.translation_speed, limits.rotation_speed};
  double tau_per_frame = 1 / (limits.rate_hz * worstStepRatio(sample(path, 6000, kStep), per_step));
  std::vector<Eigen::Isometry3f> poses = sample(path, frames, tau_per_frame);
  double ratio = worstStepRatio(poses, limits);
  for (int k = 0; k < 20 && (ratio > 1 || ratio < 0.99); ++k) {
    tau_per_frame /= ratio * 1.0001;
    poses = sample(path, frames, tau_per_frame);
    ratio = worstStepRatio(poses, limits);
  }
  while (ratio > 1) {  // never above the limit, even where the scaling has not settled
    tau_per_frame /= ratio * 1.001;
    poses = sample(path, frames, tau_per_frame);
    ratio = worstStepRatio(poses, limits);
  }
  return poses;
}

}  // namespace stocs
