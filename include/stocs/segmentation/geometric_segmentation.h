#pragma once
// Segmentation from depth alone, for objects no network knows: the supporting planes are removed
// (PCL's OrganizedMultiPlaneSegmentation), depth-discontinuity and curvature edges cut the rest
// (PCL's organized edge detection), and each connected region left is an object candidate. An
// object's probability map is the union of the candidates of a size that can hold it, softened as
// a hard mask is (maskProbability), so StoCS keeps its tolerance to segmentation errors.

#include <Eigen/Core>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "stocs/geometry/camera.h"
#include "stocs/geometry/organized_cloud.h"
#include "stocs/segmentation/chromaticity.h"
#include "stocs/util/param_set.h"

namespace stocs {

struct GeometricSegmentationParams {
  /// Every this many pixels along each axis are segmented (2: a quarter of them), the regions then
  /// brought back to the full image; 1: every pixel.
  int stride = 2;
  /// Pixels of the full image: the window of PCL's integral-image normals (their smoothing).
  float normal_smoothing_px = 10.0f;
  /// Share of the depth: a step larger than this between neighbours is not smoothed over by the
  /// normals and is a depth-discontinuity edge.
  float depth_discontinuity = 0.02f;
  /// A plane of at least this area (m^2) is a supporting surface (table, bin floor, wall) and is
  /// removed; smaller planes are object faces.
  float plane_min_area = 0.05f;
  /// Degrees: neighbouring normals within this angle grow one plane (loose: a noisier sensor's
  /// normals part by several degrees on a table, while a crease between faces turns faster).
  float plane_angle_deg = 10.0f;
  /// Metres: a point this close to a supporting plane (and facing as it does) belongs to it.
  float plane_distance = 0.008f;
  /// Degrees: where the normals of neighbours turn by more than this in a valley (a concave
  /// crease, where touching objects meet), that is an edge too; 180: no crease edges.
  float crease_angle_deg = 30.0f;
  /// Pixels of the full image: edges are widened by this before the regions are grown (a thin
  /// bridge does not join two objects); 0: as detected.
  int edge_dilation_px = 1;
  /// Pixels of the full image: a connected region of fewer is noise, not a candidate.
  int min_region_px = 150;
  /// A candidate can hold an object when its 3D extent lies between these shares of the object's
  /// diameter: above the lower one (a part large enough to estimate on) ...
  float min_extent_share = 0.2f;
  /// ... and below the upper one (noise and the sensor's flying pixels widen a region a little);
  /// its thinnest width must also stay below this share of the object's plus width_margin.
  float max_extent_share = 1.3f;
  /// Metres: the sensor's noise added to what a region may be thicker than the object.
  float width_margin = 0.01f;
  /// A candidate that can hold the object scores by how its extent matches the object's visible
  /// extent (about 0.95 of its diameter): a bell of this deviation in ln(extent / visible extent).
  /// Sampling and scoring weigh it by that, so a region of the object's size comes first.
  float size_sigma = 0.15f;
  /// Where the frame and the object's model have colour, a candidate's score is scaled by
  /// 1 - colour_weight + colour_weight x the share of the object's colours it holds
  /// (ChromaticityHistogram::overlap): a region of the object's size and of other colours falls
  /// behind one of its colours. 0: colour is ignored.
  float colour_weight = 0.8f;
  /// ... and scores at least this (above estimation.segment.min_probability: it stays a candidate).
  float min_region_score = 0.25f;
  /// Softening of each candidate as a hard mask (SegmentationInputParams): the border's blur ...
  float border_px = 3.0f;
  /// ... the least probability inside ...
  float inside_floor = 0.6f;
  /// ... and the probability everywhere else (0: StoCS never samples outside the candidates).
  float outside_floor = 0.0f;

  /// Key, range, unit and meaning of every field.
  static const ParamSet<GeometricSegmentationParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
};

/// The size of an object model, which a region must be able to hold.
struct ObjectSize {
  float diameter = 0;   ///< metres: the largest distance across the model
  float min_width = 0;  ///< metres: its thinnest width (pointSetMinWidth)

  /// Of a model's points (metres, e.g. ObjectModel::points or a mesh's vertices).
  static ObjectSize of(const std::vector<Eigen::Vector3f>& points);
};

/// One connected region of the depth image that is neither plane nor edge.
struct DepthRegion {
  cv::Mat mask;              ///< CV_8UC1, 255 inside, the depth image's size
  cv::Rect box;              ///< its bounding box in the image
  int pixels = 0;            ///< its area
  float extent = 0;          ///< metres: the largest distance across its points (approximate)
  float min_width = 0;       ///< metres: its thinnest width (pointSetMinWidth)
  Eigen::Vector3f centroid;  ///< metres, camera frame
  /// Its pixels' colours (addRegionColours); empty without a colour image.
  ChromaticityHistogram colours;
};

/// Two regions that touch (across an edge band at most): perhaps one object that its own edges cut
/// in two, as a mug's rim cuts its inside from its outside.
struct AdjacentRegions {
  size_t first = 0, second = 0;  ///< indices into GeometricSegmentation::regions, first < second
  float extent = 0;              ///< metres: the largest distance across both (approximate)
  float min_width = 0;           ///< metres: their thinnest width together
};

/// What the segmentation found in one frame.
struct GeometricSegmentation {
  std::vector<DepthRegion> regions;  ///< the object candidates, largest first
  /// Every pair of regions that touch; the pair is a candidate of its own for an object it fits
  /// better than either region alone (objectProbability).
  std::vector<AdjacentRegions> adjacent;
  cv::Mat plane_mask;  ///< CV_8UC1, 255 on the supporting planes
  cv::Mat edge_mask;   ///< CV_8UC1, 255 on the (widened) edges
  int planes = 0;      ///< supporting planes removed
};

/// Segments frame after frame; it keeps PCL's buffers from one frame to the next (allocating them
/// anew costs more than the work). Not for several threads at once.
class GeometricSegmenter {
 public:
  /// Throws InputError naming the first parameter out of range.
  explicit GeometricSegmenter(const GeometricSegmentationParams& params = {});
  ~GeometricSegmenter();
  GeometricSegmenter(GeometricSegmenter&&) noexcept;
  GeometricSegmenter& operator=(GeometricSegmenter&&) noexcept;

  const GeometricSegmentationParams& params() const { return params_; }

  /// Segments an organized cloud (NaN where nothing was measured) taken by `camera`. Throws
  /// InputError for an empty cloud, one without a valid point, or intrinsics that are not finite
  /// and positive or not of the cloud's size.
  GeometricSegmentation segment(const OrganizedCloud& cloud, const CameraIntrinsics& camera);
  /// The same from a depth image (CV_16UC1 or CV_32FC1, `metres_per_unit` per value; 0 or NaN: no
  /// measurement). Throws InputError for an empty image, another type, a size not the camera's or
  /// a `metres_per_unit` that is not finite and positive, and as the overload above.
  GeometricSegmentation segment(const cv::Mat& depth, const CameraIntrinsics& camera,
                                double metres_per_unit);

  struct Pcl;  ///< PCL's estimators (defined where PCL is included)

 private:
  GeometricSegmentationParams params_;
  std::unique_ptr<Pcl> pcl_;
};

/// Whether a region can hold an object of `size`: its extent within the params' shares of the
/// diameter, and it is no thicker than the object (with the margins).
bool regionFits(const DepthRegion& region, const ObjectSize& size,
                const GeometricSegmentationParams& params);

/// The soft map (CV_32FC1 in [0, 1]) of one region: 1 inside, falling off at its border.
cv::Mat regionProbability(const GeometricSegmentation& segmentation, size_t region,
                          const GeometricSegmentationParams& params);

/// Fills each region's colours from `bgr` (CV_8UC3, the segmented image's size, registered with
/// it). Throws InputError for another type or size.
void addRegionColours(GeometricSegmentation& segmentation, const cv::Mat& bgr);

/// The probability map of an object of `size`: the regions that can hold it (regionFits), each
/// softened with the score of its extent against the object's (size_sigma), scaled by colour
/// where the region and `colours` (the model's; null or empty: none) have it (colour_weight);
/// and each pair of adjacent regions whose union can hold it and scores higher than either region
/// alone, as one region; the outside floor everywhere when none can. Throws InputError for a
/// diameter that is not finite and positive, or a width that is not finite and non-negative.
cv::Mat objectProbability(const GeometricSegmentation& segmentation, const ObjectSize& size,
                          const GeometricSegmentationParams& params,
                          const ChromaticityHistogram* colours = nullptr);

}  // namespace stocs
