#include "stocs/estimation/silhouette_support.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace stocs {
namespace {

struct ProjectedSample {
  cv::Point2f pixel;
  float radius;  ///< pixels
};

std::vector<ProjectedSample> projectFacing(const ObjectModel& model, const Eigen::Isometry3f& pose,
                                           const CameraIntrinsics& camera) {
  std::vector<ProjectedSample> out;
  out.reserve(model.size());
  for (size_t i = 0; i < model.size(); ++i) {
    const Eigen::Vector3f p = pose * model.points[i];
    if (p.z() <= 0 || (pose.linear() * model.normals[i]).dot(p) >= 0) continue;
    const Eigen::Vector2f uv = camera.project(p);
    const float radius =
        std::max(1.0f, static_cast<float>(model.sampling_radius * camera.fx / p.z()));
    out.push_back({{uv.x(), uv.y()}, radius});
  }
  return out;
}

/// The pixel box of the discs, widened by a quarter of its size on each side, within the image.
cv::Rect widenedBox(const std::vector<ProjectedSample>& samples, const cv::Size& image) {
  float x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (const ProjectedSample& s : samples) {
    x0 = std::min(x0, s.pixel.x - s.radius);
    y0 = std::min(y0, s.pixel.y - s.radius);
    x1 = std::max(x1, s.pixel.x + s.radius);
    y1 = std::max(y1, s.pixel.y + s.radius);
  }
  const float wx = (x1 - x0) / 4, wy = (y1 - y0) / 4;
  const cv::Rect box(
      cv::Point(static_cast<int>(std::floor(x0 - wx)), static_cast<int>(std::floor(y0 - wy))),
      cv::Point(static_cast<int>(std::ceil(x1 + wx)) + 1,
                static_cast<int>(std::ceil(y1 + wy)) + 1));
  return box & cv::Rect(cv::Point(0, 0), image);
}

}  // namespace

float silhouetteShare(const ObjectModel& model, const Eigen::Isometry3f& pose,
                      const CameraIntrinsics& camera, const cv::Mat& probability) {
  const std::vector<ProjectedSample> samples = projectFacing(model, pose, camera);
  if (samples.empty()) return 0;
  const cv::Rect box = widenedBox(samples, probability.size());
  if (box.empty()) return 0;
  const cv::Mat map = probability(box);
  const double around = cv::sum(map)[0];
  if (!(around > 0)) return 0;
  cv::Mat silhouette = cv::Mat::zeros(box.size(), CV_8U);
  const cv::Point2f origin(static_cast<float>(box.x), static_cast<float>(box.y));
  constexpr int kShift = 4;  // sub-pixel centres and radii for cv::circle
  for (const ProjectedSample& s : samples) {
    const cv::Point2f c = (s.pixel - origin) * static_cast<float>(1 << kShift);
    cv::circle(silhouette, cv::Point(cvRound(c.x), cvRound(c.y)), cvRound(s.radius * (1 << kShift)),
               cv::Scalar(1), cv::FILLED, cv::LINE_8, kShift);
  }
  cv::Mat masked;
  map.copyTo(masked, silhouette);
  return static_cast<float>(std::min(1.0, cv::sum(masked)[0] / around));
}

}  // namespace stocs
