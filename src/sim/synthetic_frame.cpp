#include "stocs/sim/synthetic_frame.h"

#include <fmt/format.h>

#include "stocs/sim/depth_renderer.h"
#include "stocs/util/error.h"
#include "stocs/util/random.h"

namespace stocs {
namespace {

const cv::Vec3b kTableColour(150, 160, 170);
const cv::Vec3b kBackgroundColour(40, 40, 40);

/// The support plane z = 0, 1.6 m square, in 10 cm tiles: the renderer skips a triangle that
/// reaches behind the camera, so a few large triangles would leave holes in the table.
constexpr int kTiles = 16;
constexpr float kTile = 0.1f, kHalf = kTiles * kTile / 2;

MeshData tableTop() {
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

/// The surface colour (BGR) at a pixel of an object: the mesh's own where it has one, else
/// `plain`.
cv::Vec3b objectColour(const DepthRenderer& renderer, int u, int v, const cv::Vec3b& plain) {
  if (renderer.colours().empty()) return plain;
  const cv::Vec4b rgba = renderer.colours().at<cv::Vec4b>(v, u);
  return rgba[3] == 0 ? plain : cv::Vec3b(rgba[2], rgba[1], rgba[0]);
}

}  // namespace

CameraIntrinsics defaultSynthCamera() {
  return {615.0, 615.0, 319.5, 239.5, 640, 480};
}

SyntheticFrame renderSyntheticFrame(const std::vector<PlacedObject>& objects,
                                    const std::vector<cv::Vec3b>& colours,
                                    const Eigen::Isometry3f& camera_pose,
                                    const CameraIntrinsics& camera, const DepthNoiseParams& noise,
                                    const SceneLook& look, uint64_t seed) {
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

  const cv::Mat table_colours = tableColours(look, kTableColour, camera_pose, camera, kHalf);
  frame.rgb = look.background.empty()
                  ? cv::Mat(camera.height, camera.width, CV_8UC3, kBackgroundColour)
                  : look.background.clone();
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const int l = renderer.labels().at<int>(v, u);
      if (l == 0) continue;
      const cv::Vec3b base = l == table_label ? table_colours.at<cv::Vec3b>(v, u)
                                              : objectColour(renderer, u, v, colours[l - 1]);
      frame.rgb.at<cv::Vec3b>(v, u) = shade(base, renderer.normals().at<cv::Vec3f>(v, u), look);
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
