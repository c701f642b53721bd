#include "stocs/sim/synthetic_frame.h"

#include <fmt/format.h>

#include "stocs/sim/depth_renderer.h"
#include "stocs/util/error.h"
#include "stocs/util/random.h"

namespace stocs {
namespace {

const cv::Vec3b kTableColour(150, 160, 170);
const cv::Vec3b kBackgroundColour(40, 40, 40);

/// Diffuse shading under a light above and behind the camera, plus ambient light.
cv::Vec3b shade(const cv::Vec3b& colour, const cv::Vec3f& normal, const Eigen::Vector3f& light) {
  const float diffuse =
      std::max(0.0f, -Eigen::Vector3f(normal[0], normal[1], normal[2]).dot(light));
  const float gain = 0.35f + 0.65f * diffuse;
  return cv::Vec3b(cv::saturate_cast<uint8_t>(colour[0] * gain),
                   cv::saturate_cast<uint8_t>(colour[1] * gain),
                   cv::saturate_cast<uint8_t>(colour[2] * gain));
}

/// The support plane z = 0, 1.6 m square, in 10 cm tiles: the renderer skips a triangle that
/// reaches behind the camera, so a few large triangles would leave holes in the table.
MeshData tableTop() {
  constexpr int kTiles = 16;
  constexpr float kTile = 0.1f, kHalf = kTiles * kTile / 2;
  MeshData plane;
  for (int y = 0; y <= kTiles; ++y) {
    for (int x = 0; x <= kTiles; ++x)
      plane.vertices.emplace_back(x * kTile - kHalf, y * kTile - kHalf, 0);
  }
  for (int y = 0; y < kTiles; ++y) {
    for (int x = 0; x < kTiles; ++x) {
      const int a = y * (kTiles + 1) + x, b = a + 1, c = a + kTiles + 2, d = a + kTiles + 1;
      plane.triangles.emplace_back(a, b, c);
      plane.triangles.emplace_back(a, c, d);
    }
  }
  return plane;
}

}  // namespace

CameraIntrinsics defaultSynthCamera() {
  return {615.0, 615.0, 319.5, 239.5, 640, 480};
}

SyntheticFrame renderSyntheticFrame(const std::vector<PlacedObject>& objects,
                                    const std::vector<cv::Vec3b>& colours,
                                    const Eigen::Isometry3f& camera_pose,
                                    const CameraIntrinsics& camera, const DepthNoiseParams& noise,
                                    uint64_t seed) {
  if (colours.size() != objects.size()) {
    throw InputError(
        fmt::format("synthetic frame: {} colours for {} objects", colours.size(), objects.size()));
  }
  DepthRenderer renderer(camera);
  SyntheticFrame frame;
  const int table_label = static_cast<int>(objects.size()) + 1;
  for (size_t i = 0; i < objects.size(); ++i) {
    renderer.draw(objects[i].mesh, camera_pose * objects[i].pose, static_cast<int>(i) + 1);
    DepthRenderer alone(camera);
    alone.draw(objects[i].mesh, camera_pose * objects[i].pose, 1);
    frame.silhouette_pixels.push_back(cv::countNonZero(alone.labels()));
  }
  static const MeshData table = tableTop();
  renderer.draw(table, camera_pose, table_label);

  frame.exact_depth = renderer.depth().clone();
  frame.labels = renderer.labels().clone();
  frame.labels.setTo(0, frame.labels == table_label);
  frame.depth =
      applyDepthNoise(frame.exact_depth, renderer.normals(), camera, noise, streamSeed(seed, 0));

  const Eigen::Vector3f light = Eigen::Vector3f(0.3f, 0.6f, 1.0f).normalized();  // camera frame
  frame.rgb = cv::Mat(camera.height, camera.width, CV_8UC3, kBackgroundColour);
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const int l = renderer.labels().at<int>(v, u);
      if (l == 0) continue;
      const cv::Vec3b base = l == table_label ? kTableColour : colours[l - 1];
      frame.rgb.at<cv::Vec3b>(v, u) = shade(base, renderer.normals().at<cv::Vec3f>(v, u), light);
    }
  }
  cv::Mat grain(frame.rgb.size(), CV_16SC3);
  cv::RNG rng(streamSeed(seed, 1));
  rng.fill(grain, cv::RNG::NORMAL, 0, 3);
  cv::Mat rgb16;
  frame.rgb.convertTo(rgb16, CV_16SC3);
  cv::Mat(rgb16 + grain).convertTo(frame.rgb, CV_8UC3);
  return frame;
}

}  // namespace stocs
