#pragma once
// One frame of a BOP dataset, loaded for playback as sensor data (ROS-free): depth in metres, the
// organized cloud, the colour image, per-object probability maps (from a stocs::ProbabilitySource:
// the dataset's prob/ maps or the segmentation simulator) and the boundary map.

#include <opencv2/core.hpp>
#include <vector>

#include "stocs/geometry/camera.h"
#include "stocs/geometry/organized_cloud.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/sim/probability_source.h"

namespace stocs_ros {

struct BopFrame {
  stocs::CameraIntrinsics camera;
  cv::Mat depth;  ///< CV_32FC1, metres, NaN where nothing was measured (REP 118)
  stocs::OrganizedCloud cloud;
  cv::Mat bgr;  ///< CV_8UC3 colour image of the same size, or empty when the frame has none
  /// CV_32FC1 in [0, 1], one per requested object id; all zero where the source has no map (the
  /// network saw no such object).
  std::vector<cv::Mat> probabilities;
  std::vector<int> objects_without_map;  ///< the requested ids whose map is all zero for that
  cv::Mat boundary;  ///< CV_8UC1, 255 interior; empty when the frame has no edge/ map
};

/// Throws stocs::InputError naming the file at fault.
BopFrame loadBopFrame(const stocs::BopDataset& dataset, int scene, int image,
                      const stocs::BopFrameCamera& camera, const std::vector<int>& object_ids,
                      const stocs::ProbabilitySource& probabilities);

}  // namespace stocs_ros
