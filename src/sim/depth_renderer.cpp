#include "stocs/sim/depth_renderer.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "stocs/util/error.h"

namespace stocs {

DepthRenderer::DepthRenderer(const CameraIntrinsics& camera) : camera_(camera) {
  if (!camera.valid()) throw InputError("renderer: camera intrinsics are invalid");
  depth_ = cv::Mat(camera.height, camera.width, CV_32FC1, cv::Scalar(0));
  labels_ = cv::Mat(camera.height, camera.width, CV_32SC1, cv::Scalar(0));
  normals_ = cv::Mat(camera.height, camera.width, CV_32FC3, cv::Scalar(0, 0, 0));
}

namespace {
constexpr float kNear = 0.01f;

using Rgba = Eigen::Matrix<uint8_t, 4, 1>;

/// The colour at barycentric weights `w` of triangle `t`: the weighted mean of its vertices of
/// known colour (alpha > 0), alpha 0 when none is known.
cv::Vec4b blend(const std::vector<Rgba>& colours, const Eigen::Vector3i& t,
                const Eigen::Vector3f& w) {
  Eigen::Vector4f sum = Eigen::Vector4f::Zero();
  float weight = 0;
  for (int k = 0; k < 3; ++k) {
    const Rgba& colour = colours[t[k]];
    if (colour[3] == 0) continue;
    sum += w[k] * colour.cast<float>();
    weight += w[k];
  }
  if (!(weight > 0)) return cv::Vec4b(0, 0, 0, 0);
  sum /= weight;
  return cv::Vec4b(cv::saturate_cast<uint8_t>(sum[0]), cv::saturate_cast<uint8_t>(sum[1]),
                   cv::saturate_cast<uint8_t>(sum[2]), cv::saturate_cast<uint8_t>(sum[3]));
}

}  // namespace

void DepthRenderer::draw(const MeshData& mesh, const Eigen::Isometry3f& pose, int label) {
  if (mesh.hasColour() && mesh.colours.size() != mesh.vertices.size()) {
    throw InputError(fmt::format("renderer: {} colours for {} vertices", mesh.colours.size(),
                                 mesh.vertices.size()));
  }
  if (mesh.hasColour() && colours_.empty()) {
    colours_ = cv::Mat(camera_.height, camera_.width, CV_8UC4, cv::Scalar(0, 0, 0, 0));
  }
  std::vector<Eigen::Vector3f> cam(mesh.vertices.size());
  std::vector<Eigen::Vector2f> px(mesh.vertices.size());
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    cam[i] = pose * mesh.vertices[i];
    if (cam[i].z() >= kNear) px[i] = camera_.project(cam[i]);
  }
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3f &a = cam[t[0]], &b = cam[t[1]], &c = cam[t[2]];
    if (a.z() < kNear || b.z() < kNear || c.z() < kNear) continue;
    Eigen::Vector3f normal = (b - a).cross(c - a);
    const float len = normal.norm();
    if (!(len > 0)) continue;
    normal /= len;
    if (normal.dot(a) > 0) normal = -normal;  // the side facing the camera (back faces may show)
    const Eigen::Vector2f &pa = px[t[0]], &pb = px[t[1]], &pc = px[t[2]];
    const float area = (pb - pa).x() * (pc - pa).y() - (pb - pa).y() * (pc - pa).x();
    if (std::abs(area) < 1e-9f) continue;
    const int u0 = std::max(0, static_cast<int>(std::ceil(std::min({pa.x(), pb.x(), pc.x()}))));
    const int u1 = std::min(camera_.width - 1,
                            static_cast<int>(std::floor(std::max({pa.x(), pb.x(), pc.x()}))));
    const int v0 = std::max(0, static_cast<int>(std::ceil(std::min({pa.y(), pb.y(), pc.y()}))));
    const int v1 = std::min(camera_.height - 1,
                            static_cast<int>(std::floor(std::max({pa.y(), pb.y(), pc.y()}))));
    // Perspective-correct depth: 1/z is affine in screen space.
    const float iza = 1.0f / a.z(), izb = 1.0f / b.z(), izc = 1.0f / c.z();
    for (int v = v0; v <= v1; ++v) {
      for (int u = u0; u <= u1; ++u) {
        const Eigen::Vector2f p(static_cast<float>(u), static_cast<float>(v));
        const float wa = ((pb - p).x() * (pc - p).y() - (pb - p).y() * (pc - p).x()) / area;
        const float wb = ((pc - p).x() * (pa - p).y() - (pc - p).y() * (pa - p).x()) / area;
        const float wc = 1.0f - wa - wb;
        if (wa < 0 || wb < 0 || wc < 0)
          continue;  // outside (pixel centres exactly on an edge count)
        const float z = 1.0f / (wa * iza + wb * izb + wc * izc);
        float& d = depth_.at<float>(v, u);
        if (d != 0 && d <= z) continue;
        d = z;
        labels_.at<int>(v, u) = label;
        normals_.at<cv::Vec3f>(v, u) = cv::Vec3f(normal.x(), normal.y(), normal.z());
        if (colours_.empty()) continue;
        // Perspective-correct weights: each screen weight over its vertex's depth, times z.
        colours_.at<cv::Vec4b>(v, u) =
            mesh.hasColour()
                ? blend(mesh.colours, t, Eigen::Vector3f(wa * iza, wb * izb, wc * izc) * z)
                : cv::Vec4b(0, 0, 0, 0);
      }
    }
  }
}

void DepthRenderer::drawPoints(const std::vector<Eigen::Vector3f>& points,
                               const Eigen::Isometry3f& pose, float radius, int label) {
  for (const Eigen::Vector3f& model_point : points) {
    const Eigen::Vector3f p = pose * model_point;
    if (p.z() < kNear) continue;
    const Eigen::Vector2f c = camera_.project(p);
    const float ru = static_cast<float>(radius * camera_.fx / p.z());
    const float rv = static_cast<float>(radius * camera_.fy / p.z());
    const int u0 = std::max(0, static_cast<int>(std::ceil(c.x() - ru)));
    const int u1 = std::min(camera_.width - 1, static_cast<int>(std::floor(c.x() + ru)));
    const int v0 = std::max(0, static_cast<int>(std::ceil(c.y() - rv)));
    const int v1 = std::min(camera_.height - 1, static_cast<int>(std::floor(c.y() + rv)));
    const Eigen::Vector3f to_camera = -p.normalized();
    const auto splat = [&](int u, int v) {
      float& d = depth_.at<float>(v, u);
      if (d != 0 && d <= p.z()) return;
      d = p.z();
      labels_.at<int>(v, u) = label;
      normals_.at<cv::Vec3f>(v, u) = cv::Vec3f(to_camera.x(), to_camera.y(), to_camera.z());
      if (!colours_.empty()) colours_.at<cv::Vec4b>(v, u) = cv::Vec4b(0, 0, 0, 0);
    };
    if (u0 > u1 || v0 > v1) {  // smaller than a pixel: its own pixel
      const int u = static_cast<int>(std::lround(c.x())), v = static_cast<int>(std::lround(c.y()));
      if (u >= 0 && v >= 0 && u < camera_.width && v < camera_.height) splat(u, v);
      continue;
    }
    for (int v = v0; v <= v1; ++v) {
      for (int u = u0; u <= u1; ++u) splat(u, v);
    }
  }
}

}  // namespace stocs
