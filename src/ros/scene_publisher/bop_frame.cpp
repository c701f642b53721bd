#include "stocs_ros/scene_publisher/bop_frame.h"

#include <fmt/format.h>

#include <limits>

#include "stocs/util/error.h"

namespace stocs_ros {

BopFrame loadBopFrame(const stocs::BopDataset& dataset, int scene, int image,
                      const stocs::BopFrameCamera& camera, const std::vector<int>& object_ids,
                      const stocs::ProbabilitySource& probabilities) {
  BopFrame frame;
  const cv::Mat raw = dataset.loadDepth(scene, image);
  frame.camera = camera.intrinsics(raw.cols, raw.rows);
  const double metres_per_unit = camera.depth_scale / 1000.0;
  frame.cloud = stocs::cloudFromDepth(raw, frame.camera, metres_per_unit);
  raw.convertTo(frame.depth, CV_32FC1, metres_per_unit);
  frame.depth.setTo(std::numeric_limits<float>::quiet_NaN(), raw == 0);

  frame.bgr = dataset.loadColour(scene, image, raw.size());
  for (int id : object_ids) {
    cv::Mat p;
    if (probabilities.available(scene, image, id)) {
      p = probabilities.load(scene, image, id);
    } else {
      p = cv::Mat(raw.size(), CV_32FC1, cv::Scalar(0));
      frame.objects_without_map.push_back(id);
    }
    if (p.size() != raw.size()) {
      throw stocs::InputError(
          fmt::format("{} (source '{}'): probability map is {}x{} but the depth is {}x{}",
                      dataset.probabilityPath(scene, image, id).string(), probabilities.spec(),
                      p.cols, p.rows, raw.cols, raw.rows));
    }
    frame.probabilities.push_back(p);
  }
  frame.boundary = dataset.loadBoundary(scene, image);
  return frame;
}

}  // namespace stocs_ros
