#pragma once
// The soft segment of one object (paper eqs. 1-3): the scene points whose class probability exceeds
// epsilon, each with a normal and the normalised probability pi_k.
//
// Points are voxel centroids (default 5 mm, the authors' scene resolution): a voxel's confidence is
// the mean probability of its pixels and its normal is estimated at the pixel nearest its centroid.
// This bounds the work of every later stage by the object's surface area rather than by its
// distance to the camera. Where a voxel spans many pixels (near, or a long focal length), the
// pixel scan takes every s-th row and column: a 5 mm voxel covers 9 x 9 pixels of YCB-Video at
// 0.6 m, and a few of them place its centroid as well as all 81, in less time.

#include <Eigen/Core>
#include <opencv2/core/types.hpp>
#include <optional>
#include <vector>

#include "stocs/geometry/normals.h"
#include "stocs/geometry/organized_cloud.h"
#include "stocs/util/param_set.h"

namespace cv {
class Mat;
}

namespace stocs {

struct SoftSegmentParams {
  /// epsilon of eq. (2); pixels at or below it are left out. The paper only asks for a small
  /// value. 0.2 rather than 0.1: a network map's faintest band lies mostly on clutter, whose
  /// points cost time and draw bases off the object.
  float min_probability = 0.2f;
  float voxel_size = 0.005f;  ///< metres; 0 keeps every pixel as a point
  /// Pixel samples across a voxel at the segment's far depth (the 90th percentile of its pixels'):
  /// the scan takes every s-th row and column, s = floor(voxel footprint in pixels / this), at
  /// least 1. 0 scans every pixel.
  float samples_per_voxel = 2.0f;
  OrganizedNormalParams normals;

  /// Key, range, unit and meaning of every field (docs/parameters.md).
  static const ParamSet<SoftSegmentParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
};

struct SoftSegment {
  std::vector<Eigen::Vector3f> points;   ///< camera optical frame, metres
  std::vector<Eigen::Vector3f> normals;  ///< unit, facing the camera
  std::vector<float> probability;        ///< pi_k of eq. (3): sums to 1
  std::vector<float> confidence;         ///< network probability, in (epsilon, 1]
  std::vector<int> pixel;                ///< representative pixel index (row-major)
  /// Instance region of each point when a boundary map was applied (see labelRegions): points of
  /// one region belong to one object instance; -1 marks points on a boundary. Empty otherwise.
  std::vector<int> region;

  size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
};

/// Builds the soft segment from an organized cloud and a CV_32FC1 probability image of the same
/// size (see toProbabilityImage). `focal_px` sizes the normal neighbourhoods and the voxels' pixel
/// footprint. Pixels without depth or without a normal are left out; the result may be empty.
/// Throws InputError on a size or type mismatch. The pixel scan, the representatives and the
/// normals run on `threads` threads (the merge of the chunks between them in image order); the
/// result does not depend on it. With `roi`, only the pixels inside it (clipped to the image) are
/// scanned: a tracker segments the neighbourhood of an object's predicted image alone.
SoftSegment buildSoftSegment(const OrganizedCloud& cloud, const cv::Mat& probability,
                             float focal_px, const SoftSegmentParams& params, int threads = 1,
                             const std::optional<cv::Rect>& roi = std::nullopt);

/// The pixel stride of buildSoftSegment's scan (see SoftSegmentParams::samples_per_voxel) over
/// `roi` (clipped to the image): 1 when no pixel is above epsilon. Expects the checks of
/// buildSoftSegment passed.
int segmentPixelStride(const OrganizedCloud& cloud, const cv::Mat& probability, float focal_px,
                       const SoftSegmentParams& params,
                       const std::optional<cv::Rect>& roi = std::nullopt);

/// Splits the segment into instance regions with a boundary map (CV_8UC1, same size as the image;
/// values >= 128 are object interior, lower values are boundaries, as in the StoCS `edge.png` and
/// the BOP `edge/` extension): each region is a 4-connected component of interior pixels, and a
/// point takes the region of its representative pixel. Throws InputError on a type or size
/// mismatch.
void labelRegions(SoftSegment& segment, const cv::Mat& boundary_map, int width, int height);

}  // namespace stocs
