#pragma once
// How much of the probability map around a pose the pose's silhouette explains. A map region
// larger than the object (another object's region, confused by the network) fits a small object
// anywhere on it, with its visible surface confirmed by depth; what gives it away is the map mass
// next to the silhouette that no part of the posed object accounts for.

#include <Eigen/Geometry>

#include "stocs/geometry/camera.h"
#include "stocs/model/object_model.h"

namespace cv {
class Mat;
}

namespace stocs {

/// Of the map's mass (`probability`, CV_32FC1 of the camera's size) in the box around the pose's
/// silhouette, widened by a quarter of its size on each side, the share inside the silhouette.
/// The silhouette is the camera-facing model samples projected at `pose` (model to camera), each a
/// disc of the sampling radius. 0 when the pose projects outside the image or the box holds no
/// mass.
float silhouetteShare(const ObjectModel& model, const Eigen::Isometry3f& pose,
                      const CameraIntrinsics& camera, const cv::Mat& probability);

}  // namespace stocs
