#include "stocs/sim/scene_look.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "stocs/util/random.h"

namespace stocs {
namespace {

constexpr float kPi = static_cast<float>(M_PI);
constexpr int kTableTexels = 320;  // texels along each side of the table's texture
constexpr double kGrain = 5;       // texture noise, levels

/// Streams of a look's seed: each variation draws from its own, so turning one on leaves the
/// draws of the others as they were.
enum Stream : uint64_t { kDirection = 0x100c, kIntensity, kColour, kTable, kBackground };

float uniformIn(Rng& rng, float lo, float hi) {
  return lo + (hi - lo) * uniform01(rng);
}

cv::Vec3b randomColour(Rng& rng) {
  cv::Vec3b c;
  for (int k = 0; k < 3; ++k) c[k] = static_cast<uint8_t>(uniformIn(rng, 25, 245));
  return c;
}

/// A smooth random field in about [0, 1] of `size`: uniform noise on a grid of `cells` x `cells`,
/// bicubically upsampled.
cv::Mat smoothField(Rng& rng, int cells, cv::Size size) {
  cv::Mat coarse(cells, cells, CV_32F);
  for (int i = 0; i < cells * cells; ++i) coarse.at<float>(i) = uniform01(rng);
  cv::Mat field;
  cv::resize(coarse, field, size, 0, 0, cv::INTER_CUBIC);
  return field;
}

/// `a` where `weight` is 0, `b` where it is 1, with grain.
cv::Mat mix(const cv::Vec3b& a, const cv::Vec3b& b, const cv::Mat& weight, Rng& rng) {
  cv::Mat out(weight.size(), CV_8UC3);
  cv::Mat grain(weight.size(), CV_32FC3);
  cv::RNG noise(rng());
  noise.fill(grain, cv::RNG::NORMAL, 0, kGrain);
  for (int v = 0; v < weight.rows; ++v) {
    for (int u = 0; u < weight.cols; ++u) {
      const float w = std::clamp(weight.at<float>(v, u), 0.0f, 1.0f);
      const cv::Vec3f g = grain.at<cv::Vec3f>(v, u);
      for (int k = 0; k < 3; ++k) {
        out.at<cv::Vec3b>(v, u)[k] = cv::saturate_cast<uint8_t>((1 - w) * a[k] + w * b[k] + g[k]);
      }
    }
  }
  return out;
}

/// Stripes of a random period and direction, warped like wood grain.
cv::Mat stripes(Rng& rng, cv::Size size) {
  const float period = uniformIn(rng, 3, 24), angle = uniformIn(rng, 0, kPi);
  const cv::Mat warp = smoothField(rng, 6, size) * uniformIn(rng, 0, 6);
  cv::Mat weight(size, CV_32F);
  for (int v = 0; v < size.height; ++v) {
    for (int u = 0; u < size.width; ++u) {
      const float along = u * std::cos(angle) + v * std::sin(angle);
      weight.at<float>(v, u) =
          0.5f + 0.5f * std::sin(2 * kPi * along / period + warp.at<float>(v, u));
    }
  }
  return weight;
}

/// Square tiles of a random size, alternating.
cv::Mat tiles(Rng& rng, cv::Size size) {
  const int tile = static_cast<int>(uniformIn(rng, 12, 60));
  cv::Mat weight(size, CV_32F);
  for (int v = 0; v < size.height; ++v) {
    for (int u = 0; u < size.width; ++u) weight.at<float>(v, u) = ((u / tile + v / tile) % 2);
  }
  return weight;
}

/// Plain, striped, tiled or blotched, in two random colours (stripes: one colour and a darker
/// shade of it, as wood).
cv::Mat tableTexture(Rng& rng) {
  const cv::Size size(kTableTexels, kTableTexels);
  const cv::Vec3b base = randomColour(rng);
  cv::Vec3b other = randomColour(rng);
  switch (uniformIndex(rng, 4)) {
    case 0:
      return mix(base, other, cv::Mat::zeros(size, CV_32F), rng);
    case 1:
      other = base * uniformIn(rng, 0.55f, 0.85f);
      return mix(base, other, stripes(rng, size), rng);
    case 2:
      return mix(base, other, tiles(rng, size), rng);
    default:
      return mix(base, other, smoothField(rng, 4 + uniformIndex(rng, 12), size), rng);
  }
}

/// What lies beyond the table: two random colours blended by a smooth field, as walls and
/// furniture out of focus.
cv::Mat backgroundImage(Rng& rng, const CameraIntrinsics& camera) {
  const cv::Vec3b a = randomColour(rng), b = randomColour(rng);
  const int cells = 2 + static_cast<int>(uniformIndex(rng, 7));
  return mix(a, b, smoothField(rng, cells, cv::Size(camera.width, camera.height)), rng);
}

/// 1 + a number drawn in [-spread, spread].
float factor(Rng& rng, float spread) {
  return 1 + uniformIn(rng, -spread, spread);
}

}  // namespace

const ParamSet<SceneLookParams>& SceneLookParams::schema() {
  using P = SceneLookParams;
  static const ParamSet<P> schema =
      ParamSet<P>()
          .add(&P::light_direction_deg, "light_direction_deg", "deg", ParamRange::closed(0, 80),
               "each image's light comes from a direction drawn within this angle of the default "
               "(above and behind the camera)")
          .flag("--light-direction")
          .add(&P::light_intensity, "light_intensity", "", ParamRange::closed(0, 0.9),
               "each image's direct and ambient light are each scaled by a factor drawn in 1 +- "
               "this")
          .flag("--light-intensity")
          .add(&P::light_colour, "light_colour", "", ParamRange::closed(0, 0.5),
               "each channel of each image's light is scaled by a factor drawn in 1 +- this")
          .flag("--light-colour")
          .add(&P::backgrounds, "backgrounds",
               "each image's table gets a random colour and texture (plain, stripes, tiles or "
               "blotches) and a random smooth colour field lies beyond it")
          .flag("--backgrounds")
          .add(&P::lookalike_share, "lookalike_share", "", ParamRange::closed(0, 1),
               "share of the distractors coloured near a dataset object of the scene (the others "
               "take a random colour)")
          .flag("--lookalike-share")
          .add(&P::lookalike_jitter, "lookalike_jitter", "levels", ParamRange::closed(0, 127),
               "a look-alike distractor's channels lie within this many levels of the object's")
          .flag("--lookalike-jitter");
  return schema;
}

SceneLook drawSceneLook(const SceneLookParams& params, const CameraIntrinsics& camera,
                        uint64_t seed) {
  SceneLook look;
  if (params.light_direction_deg > 0) {
    Rng rng(streamSeed(seed, kDirection));
    // Turned by up to the angle about a random axis across the default direction.
    const Eigen::Vector3f axis =
        Eigen::AngleAxisf(uniformIn(rng, 0, 2 * kPi), look.light) * look.light.unitOrthogonal();
    const float angle = uniformIn(rng, 0, params.light_direction_deg) * kPi / 180;
    look.light = Eigen::AngleAxisf(angle, axis) * look.light;
  }
  if (params.light_intensity > 0) {
    Rng rng(streamSeed(seed, kIntensity));
    look.direct *= factor(rng, params.light_intensity);
    look.ambient *= factor(rng, params.light_intensity);
  }
  if (params.light_colour > 0) {
    Rng rng(streamSeed(seed, kColour));
    for (int k = 0; k < 3; ++k) look.light_colour[k] = factor(rng, params.light_colour);
  }
  if (params.backgrounds) {
    Rng table(streamSeed(seed, kTable)), background(streamSeed(seed, kBackground));
    look.table = tableTexture(table);
    look.background = backgroundImage(background, camera);
  }
  return look;
}

cv::Vec3b shade(const cv::Vec3b& colour, const cv::Vec3f& normal, const SceneLook& look) {
  const float diffuse =
      std::max(0.0f, -Eigen::Vector3f(normal[0], normal[1], normal[2]).dot(look.light));
  const float gain = look.ambient + look.direct * diffuse;
  return cv::Vec3b(cv::saturate_cast<uint8_t>(colour[0] * gain * look.light_colour[0]),
                   cv::saturate_cast<uint8_t>(colour[1] * gain * look.light_colour[1]),
                   cv::saturate_cast<uint8_t>(colour[2] * gain * look.light_colour[2]));
}

cv::Mat tableColours(const SceneLook& look, const cv::Vec3b& plain,
                     const Eigen::Isometry3f& camera_pose, const CameraIntrinsics& camera,
                     float half_width) {
  if (look.table.empty()) return cv::Mat(camera.height, camera.width, CV_8UC3, plain);
  // Each pixel's ray from the camera centre meets the table top z = 0 at one texel.
  const Eigen::Matrix3f to_table = camera_pose.linear().transpose();
  const Eigen::Vector3f centre = -(to_table * camera_pose.translation());
  const float texels_per_metre = look.table.cols / (2 * half_width);
  cv::Mat map_x(camera.height, camera.width, CV_32F), map_y(camera.height, camera.width, CV_32F);
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector3f ray =
          to_table * Eigen::Vector3f((u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy, 1);
      const float t = ray.z() < 0 ? -centre.z() / ray.z() : 0;  // 0: the pixel misses the table
      const Eigen::Vector3f hit = centre + t * ray;
      map_x.at<float>(v, u) = (hit.x() + half_width) * texels_per_metre - 0.5f;
      map_y.at<float>(v, u) = (hit.y() + half_width) * texels_per_metre - 0.5f;
    }
  }
  cv::Mat colours;
  cv::remap(look.table, colours, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return colours;
}

}  // namespace stocs
