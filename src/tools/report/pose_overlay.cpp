#include "pose_overlay.h"

#include <opencv2/imgproc.hpp>

#include "stocs/sim/depth_renderer.h"

namespace stocs::tools {

cv::Mat silhouette(const MeshData& model, const Eigen::Isometry3f& pose,
                   const CameraIntrinsics& camera) {
  if (model.isMesh()) {
    DepthRenderer renderer(camera);
    renderer.draw(model, pose, 1);
    return renderer.labels() > 0;
  }
  // Point models: splat the projected points, then close the gaps between them.
  cv::Mat mask(camera.height, camera.width, CV_8UC1, cv::Scalar(0));
  for (const Eigen::Vector3f& v : model.vertices) {
    const Eigen::Vector3f p = pose * v;
    if (p.z() <= 0) continue;
    const Eigen::Vector2f px = camera.project(p);
    const int u = static_cast<int>(std::lround(px.x()));
    const int w = static_cast<int>(std::lround(px.y()));
    if (u >= 0 && w >= 0 && u < camera.width && w < camera.height) mask.at<uint8_t>(w, u) = 255;
  }
  const cv::Mat disc = cv::getStructuringElement(cv::MORPH_ELLIPSE, {7, 7});
  cv::morphologyEx(mask, mask, cv::MORPH_CLOSE, disc);
  return mask;
}

cv::Scalar objectColour(int k) {
  // Hues spread by the golden angle stay distinct for any number of objects.
  cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar((60 + k * 111) % 180, 230, 255)), bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  const cv::Vec3b c = bgr.at<cv::Vec3b>(0, 0);
  return {static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2])};
}

namespace {

void outline(cv::Mat& image, const cv::Mat& mask, const cv::Scalar& colour, int thickness) {
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  cv::drawContours(image, contours, -1, colour, thickness, cv::LINE_8);
}

}  // namespace

cv::Mat drawPoseOverlay(const cv::Mat& background, const CameraIntrinsics& camera,
                        const std::vector<OverlayObject>& objects) {
  cv::Mat image = background.clone();
  for (const OverlayObject& o : objects) {
    for (const Eigen::Isometry3f& pose : o.estimates) {
      const cv::Mat mask = silhouette(*o.model, pose, camera);
      cv::Mat tinted = image.clone();
      tinted.setTo(o.colour, mask);
      cv::addWeighted(image, 0.5, tinted, 0.5, 0, image);
      outline(image, mask, o.colour, 2);
    }
  }
  for (const OverlayObject& o : objects) {  // truth last, so that it stays visible
    for (const Eigen::Isometry3f& pose : o.truths) {
      outline(image, silhouette(*o.model, pose, camera), cv::Scalar(255, 255, 255), 1);
    }
  }
  return image;
}

}  // namespace stocs::tools
