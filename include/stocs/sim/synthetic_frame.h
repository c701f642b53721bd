#pragma once
// One generated RGB-D image of a tabletop arrangement: z-buffer rendering of the objects and the
// support plane, a simple shaded colour image, and the depth camera's errors.

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "stocs/geometry/camera.h"
#include "stocs/sim/depth_noise.h"
#include "stocs/sim/scene_layout.h"
#include "stocs/sim/scene_look.h"

namespace stocs {

/// 640 x 480 with the focal length and principal point of a typical RealSense or Kinect.
CameraIntrinsics defaultSynthCamera();

struct SyntheticFrame {
  cv::Mat depth;        ///< CV_32FC1, metres, 0 = no measurement, with the sensor's errors
  cv::Mat exact_depth;  ///< CV_32FC1, metres, as rendered
  cv::Mat rgb;  ///< CV_8UC3 (BGR): each object in its vertex colours or its colour, diffuse shading
  cv::Mat labels;  ///< CV_32SC1: 1 + index of the visible object, 0 for table and background
  std::vector<long> silhouette_pixels;  ///< pixels of each object seen alone (no occlusion)
};

/// Renders `objects` (table frame) with `colours` (BGR, one per object, for the surface of a mesh
/// without vertex colours or of unknown colour) on a support plane
/// through a camera at `camera_pose` (table to camera), lit and backed as `look` says (the default
/// look: a grey table on a dark background). Deterministic for a seed.
SyntheticFrame renderSyntheticFrame(const std::vector<PlacedObject>& objects,
                                    const std::vector<cv::Vec3b>& colours,
                                    const Eigen::Isometry3f& camera_pose,
                                    const CameraIntrinsics& camera, const DepthNoiseParams& noise,
                                    const SceneLook& look, uint64_t seed);

}  // namespace stocs
