#include "stocs/sim/depth_noise.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "stocs/util/error.h"

namespace stocs {

DepthNoiseParams DepthNoiseParams::atLevel(float level) const {
  DepthNoiseParams p = *this;
  if (!(level > 0)) {
    p.sigma_min = p.sigma_quadratic = p.quantisation = 0;
    p.edge_dropout = p.dropout = 0;
    p.grazing_angle_deg = 90;
    return p;
  }
  p.sigma_min *= level;
  p.sigma_quadratic *= level;
  p.edge_dropout = std::min(1.0f, p.edge_dropout * level);
  p.dropout = std::min(1.0f, p.dropout * level);
  return p;
}

const ParamSet<DepthNoiseParams>& DepthNoiseParams::schema() {
  using P = DepthNoiseParams;
  static const ParamSet<P> schema =
      ParamSet<P>()
          .add(&P::sigma_min, "sigma_min", "m", ParamRange::closed(0, 0.1),
               "axial noise standard deviation at 0.4 m")
          .add(&P::sigma_quadratic, "sigma_quadratic", "1/m", ParamRange::closed(0, 0.1),
               "growth of the axial noise with the square of the depth beyond 0.4 m")
          .add(&P::quantisation, "quantisation", "1/m", ParamRange::closed(0, 0.1),
               "disparity quantisation: a depth step of this times depth squared")
          .add(&P::edge_jump, "edge_jump", "m", ParamRange::closed(1e-4, 10),
               "depth difference between neighbours that makes a depth edge")
          .add(&P::edge_radius, "edge_radius", "px", ParamRange::closed(0, 10),
               "pixels around a depth edge that may lose their depth")
          .add(&P::edge_dropout, "edge_dropout", "", ParamRange::closed(0, 1),
               "probability that a pixel at a depth edge has no depth")
          .add(&P::grazing_angle_deg, "grazing_angle_deg", "deg", ParamRange::closed(0, 90),
               "surfaces seen at a larger angle to their normal have no depth")
          .add(&P::dropout, "dropout", "", ParamRange::closed(0, 1),
               "probability that any pixel has no depth");
  return schema;
}

void DepthNoiseParams::validate() const {
  schema().validate(*this, [](const ParamInfo& info) { return "depth noise: " + info.key; });
}

cv::Mat applyDepthNoise(const cv::Mat& depth, const cv::Mat& normals,
                        const CameraIntrinsics& camera, const DepthNoiseParams& p, uint64_t seed) {
  p.validate();
  if (depth.type() != CV_32FC1 || normals.type() != CV_32FC3 || depth.size() != normals.size() ||
      depth.cols != camera.width || depth.rows != camera.height) {
    throw InputError(fmt::format(
        "depth noise: needs a CV_32FC1 depth and a CV_32FC3 normal image of the camera's {}x{}; "
        "got {}x{} and {}x{}",
        camera.width, camera.height, depth.cols, depth.rows, normals.cols, normals.rows));
  }
  cv::RNG rng(seed);
  const float cos_grazing = std::cos(p.grazing_angle_deg * static_cast<float>(M_PI) / 180);
  cv::Mat out(depth.size(), CV_32FC1, cv::Scalar(0));
  for (int v = 0; v < depth.rows; ++v) {
    for (int u = 0; u < depth.cols; ++u) {
      const float z = depth.at<float>(v, u);
      // Draws happen for every pixel in the same order, so a pixel's noise does not depend on
      // whether its neighbours were dropped.
      const double gaussian = rng.gaussian(1.0);
      const float chance = rng.uniform(0.0f, 1.0f), edge_chance = rng.uniform(0.0f, 1.0f);
      if (!(z > 0)) continue;
      const cv::Vec3f n = normals.at<cv::Vec3f>(v, u);
      const Eigen::Vector3f ray =
          Eigen::Vector3f(static_cast<float>((u - camera.cx) / camera.fx),
                          static_cast<float>((v - camera.cy) / camera.fy), 1.0f)
              .normalized();
      if (std::abs(ray.dot(Eigen::Vector3f(n[0], n[1], n[2]))) < cos_grazing) continue;
      if (chance < p.dropout) continue;
      bool edge = false;
      for (int dv = -p.edge_radius; dv <= p.edge_radius && !edge; ++dv) {
        for (int du = -p.edge_radius; du <= p.edge_radius && !edge; ++du) {
          const int uu = u + du, vv = v + dv;
          if (uu < 0 || vv < 0 || uu >= depth.cols || vv >= depth.rows) continue;
          const float zn = depth.at<float>(vv, uu);
          edge = !(zn > 0) || std::abs(zn - z) > p.edge_jump;
        }
      }
      if (edge && edge_chance < p.edge_dropout) continue;
      const float sigma = p.sigma_min + p.sigma_quadratic * (z - 0.4f) * (z - 0.4f);
      float measured = z + sigma * static_cast<float>(gaussian);
      if (p.quantisation > 0 && measured > 0) {
        // Disparity is proportional to 1 / z; its steps are k wide in 1 / z.
        measured = 1.0f / (std::round(1.0f / (measured * p.quantisation)) * p.quantisation);
      }
      out.at<float>(v, u) = measured > 0 ? measured : 0.0f;
    }
  }
  return out;
}

}  // namespace stocs
