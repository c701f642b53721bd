// Depth-only segmentation (geometric_segmentation.h): PCL for normals, planes and depth edges,
// OpenCV for creases, connected regions and the softening.
#include "stocs/segmentation/geometric_segmentation.h"

#include <fmt/format.h>
#include <pcl/features/integral_image_normal.h>
#include <pcl/features/normal_3d.h>
#include <pcl/features/organized_edge_detection.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/segmentation/organized_multi_plane_segmentation.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <set>

#include "stocs/geometry/mesh.h"
#include "stocs/io/segmentation_inputs.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

using PclCloud = pcl::PointCloud<pcl::PointXYZ>;
using PclNormals = pcl::PointCloud<pcl::Normal>;
using PclLabels = pcl::PointCloud<pcl::Label>;

/// At most this many points of a region go into its extent (pointSetDiameter's cost is linear).
constexpr size_t kExtentSamples = 300;
/// Degrees: a point near a supporting plane belongs to it unless its normal turns farther than
/// this from the plane's (an object's side standing on it).
constexpr float kPlaneFacingDeg = 30.0f;
/// A plane's points bend less than this (PCL's curvature of the fit: smallest eigenvalue over the
/// sum); sensor noise on a table stays far below it.
constexpr double kPlaneMaxCurvature = 0.005;
/// Metres at 1 m (PCL scales it by the depth squared): neighbours whose plane offsets (n . p)
/// differ by less grow one plane. Loose, as the offset moves by |p| times the normals' noise (a
/// table seen through 2.5 times a Kinect's noise broke into small pieces at 0.03); the plane's
/// points are then taken by distance (plane_distance).
constexpr float kPlaneGrowDistance = 0.1f;
/// Times a plane is fitted again to the surface it spreads over before it is found too small.
constexpr int kPlaneRefits = 2;
/// An unoccluded object's visible surface spans about this share of its diameter (0.93-1.0 for the
/// six objects of the generated development scenes, seeds 1-3).
constexpr float kVisibleShare = 0.95f;
/// Pixels of the full image: regions this close touch (AdjacentRegions), across the edge band left
/// where growIntoEdges stopped at a depth step.
constexpr int kTouchPx = 4;
/// Neighbours PCL's depth-edge detection searches for a valid depth across a gap.
constexpr int kEdgeSearchNeighbours = 10;

float radians(float degrees) {
  return degrees * static_cast<float>(M_PI) / 180.0f;
}

void checkInput(const OrganizedCloud& cloud, const CameraIntrinsics& camera) {
  if (cloud.width <= 0 || cloud.height <= 0) throw InputError("depth cloud is empty");
  const bool finite = std::isfinite(camera.fx) && std::isfinite(camera.fy) &&
                      std::isfinite(camera.cx) && std::isfinite(camera.cy);
  if (!finite || !camera.valid()) {
    throw InputError(
        fmt::format("camera intrinsics fx {} fy {} cx {} cy {} are not finite and positive",
                    camera.fx, camera.fy, camera.cx, camera.cy));
  }
  if (camera.width != cloud.width || camera.height != cloud.height) {
    throw InputError(fmt::format("depth cloud is {}x{} but the camera is {}x{}", cloud.width,
                                 cloud.height, camera.width, camera.height));
  }
  if (cloud.points.size() != static_cast<size_t>(cloud.width) * cloud.height) {
    throw InputError(fmt::format("depth cloud has {} points for {}x{} pixels", cloud.points.size(),
                                 cloud.width, cloud.height));
  }
  if (cloud.validCount() == 0) throw InputError("depth image has no valid measurement");
}

/// Every `stride`-th pixel of the cloud along each axis, as a PCL organized cloud (NaN invalid).
PclCloud::Ptr reducedCloud(const OrganizedCloud& cloud, int stride) {
  const int w = (cloud.width + stride - 1) / stride, h = (cloud.height + stride - 1) / stride;
  PclCloud::Ptr out(new PclCloud(w, h));
  out->is_dense = false;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const int i = v * stride * cloud.width + u * stride;
      const Eigen::Vector3f& p = cloud.points[i];
      out->at(u, v) =
          cloud.isValid(i) ? pcl::PointXYZ(p.x(), p.y(), p.z()) : pcl::PointXYZ(nan, nan, nan);
    }
  }
  return out;
}

/// The intrinsics of the reduced image: pixel (u, v) there is pixel (stride u, stride v) here.
CameraIntrinsics reducedCamera(const CameraIntrinsics& camera, int stride, int width, int height) {
  CameraIntrinsics c = camera;
  c.fx /= stride;
  c.fy /= stride;
  c.cx /= stride;
  c.cy /= stride;
  c.width = width;
  c.height = height;
  return c;
}

/// Metres^2 covered by a plane's inliers: each pixel's footprint at its depth, over the cosine of
/// its view ray to the plane's normal (clamped: grazing planes are not blown up).
float planeArea(const PclCloud& cloud, const CameraIntrinsics& camera,
                const pcl::PointIndices& inliers, const Eigen::Vector3f& normal) {
  double area = 0;
  for (const int i : inliers.indices) {
    const Eigen::Vector3f p = cloud[i].getVector3fMap();
    const float cosine = std::max(0.2f, std::abs(normal.dot(p.normalized())));
    area += p.z() * p.z() / (camera.fx * camera.fy * cosine);
  }
  return static_cast<float>(area);
}

/// Whether a point lies on a supporting plane: near it and facing as it does (a point without a
/// normal by distance alone).
class OnPlane {
 public:
  OnPlane(const PclCloud& cloud, const PclNormals& normals, const Eigen::Vector4f& plane,
          float distance)
      : cloud_(cloud),
        normals_(normals),
        plane_(plane),
        distance_(distance),
        min_cos_(std::cos(radians(kPlaneFacingDeg))) {}

  bool operator()(size_t i) const {
    const Eigen::Vector3f p = cloud_[i].getVector3fMap();
    if (!std::isfinite(p.z()) || std::abs(plane_.head<3>().dot(p) + plane_[3]) > distance_) {
      return false;
    }
    const Eigen::Vector3f normal = normals_[i].getNormalVector3fMap();
    return !normal.allFinite() || std::abs(normal.dot(plane_.head<3>())) >= min_cos_;
  }

 private:
  const PclCloud& cloud_;
  const PclNormals& normals_;
  Eigen::Vector4f plane_;
  float distance_, min_cos_;
};

/// Marks the points of one supporting plane in `mask`.
void markPlane(const OnPlane& on_plane, cv::Mat& mask) {
  for (size_t i = 0; i < mask.total(); ++i) {
    if (on_plane(i)) mask.data[i] = 255;
  }
}

/// The points on the plane that connect to `seeds` (8-neighbours): the surface a plane's segment
/// lies on. A table that a noisy sensor's normals broke into segments smaller than a supporting
/// plane is taken whole; a box's top, level with the tops of others apart from it, is not.
pcl::PointIndices spreadSurface(const OnPlane& on_plane, int width, int height,
                                const pcl::PointIndices& seeds) {
  std::vector<char> visited(static_cast<size_t>(width) * height, 0);
  std::vector<int> front;
  for (const int i : seeds.indices) {
    if (!visited[i] && on_plane(i)) front.push_back(i);
    visited[i] = 1;
  }
  pcl::PointIndices surface;
  while (!front.empty()) {
    const int i = front.back();
    front.pop_back();
    surface.indices.push_back(i);
    const int u = i % width, v = i / width;
    for (int dv = -1; dv <= 1; ++dv) {
      for (int du = -1; du <= 1; ++du) {
        if (u + du < 0 || u + du >= width || v + dv < 0 || v + dv >= height) continue;
        const int j = i + dv * width + du;
        if (visited[j]) continue;
        visited[j] = 1;
        if (on_plane(j)) front.push_back(j);
      }
    }
  }
  return surface;
}

/// Whether the surface turns up into a valley between neighbours a and b: their normals (toward
/// the camera) part by more than the angle, and each lies in front of the other's tangent plane.
bool concaveCrease(const PclCloud& cloud, const PclNormals& normals, size_t a, size_t b,
                   float min_cos) {
  const Eigen::Vector3f na = normals[a].getNormalVector3fMap();
  const Eigen::Vector3f nb = normals[b].getNormalVector3fMap();
  if (!na.allFinite() || !nb.allFinite() || na.dot(nb) > min_cos) return false;
  const Eigen::Vector3f d = cloud[b].getVector3fMap() - cloud[a].getVector3fMap();
  return d.dot(na) > 0 && -d.dot(nb) > 0;
}

/// Marks the concave creases (crease_angle_deg) between pixels `step` apart to the right and
/// below, at the pixel midway (the normals are smoothed over about that many pixels).
void markCreases(const PclCloud& cloud, const PclNormals& normals, float angle_deg, int step,
                 cv::Mat& mask) {
  if (angle_deg >= 180.0f) return;
  const float min_cos = std::cos(radians(angle_deg));
  const int w = static_cast<int>(cloud.width), h = static_cast<int>(cloud.height);
  const int half = step / 2;
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const size_t i = static_cast<size_t>(v) * w + u;
      if (u + step < w && concaveCrease(cloud, normals, i, i + step, min_cos)) {
        mask.data[i + half] = 255;
      }
      if (v + step < h && concaveCrease(cloud, normals, i, i + step * w, min_cos)) {
        mask.data[i + half * w] = 255;
      }
    }
  }
}

/// Whether two points are on one surface: no depth step beyond the share between them.
bool sameSurface(const pcl::PointXYZ& a, const pcl::PointXYZ& b, float share) {
  return std::isfinite(b.z) && std::abs(a.z - b.z) <= share * a.z;
}

/// Grows the labelled regions back over the edge band they were cut by, one pixel a pass, `passes`
/// times: an unlabelled pixel of `grow` takes the label of a 4-neighbour on its surface.
void growIntoEdges(const PclCloud& cloud, const cv::Mat& grow, float share, int passes,
                   cv::Mat& labels) {
  const int w = labels.cols, h = labels.rows;
  const int du[] = {1, -1, 0, 0}, dv[] = {0, 0, 1, -1};
  for (int pass = 0; pass < passes; ++pass) {
    const cv::Mat before = labels.clone();
    for (int v = 0; v < h; ++v) {
      for (int u = 0; u < w; ++u) {
        if (!grow.at<uchar>(v, u) || before.at<int>(v, u)) continue;
        for (int k = 0; k < 4; ++k) {
          const int nu = u + du[k], nv = v + dv[k];
          if (nu < 0 || nv < 0 || nu >= w || nv >= h || !before.at<int>(nv, nu)) continue;
          if (!sameSurface(cloud.at(u, v), cloud.at(nu, nv), share)) continue;
          labels.at<int>(v, u) = before.at<int>(nv, nu);
          break;
        }
      }
    }
  }
}

/// The extent, thinnest width and centroid of a set of points.
struct RegionShape {
  float extent = 0;
  float min_width = 0;
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
};

/// The shape of the points in `box` whose label `inside` accepts (a subsample of them for the
/// extent and width), `pixels` of them.
template <class Inside>
RegionShape measureShape(const cv::Mat& labels, Inside inside, const cv::Rect& box, int pixels,
                         const PclCloud& cloud) {
  const size_t step = std::max<size_t>(1, static_cast<size_t>(pixels) / kExtentSamples);
  std::vector<Eigen::Vector3f> samples;
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  size_t seen = 0;
  for (int v = box.y; v < box.y + box.height; ++v) {
    for (int u = box.x; u < box.x + box.width; ++u) {
      if (!inside(labels.at<int>(v, u))) continue;
      const Eigen::Vector3f p = cloud.at(u, v).getVector3fMap();
      sum += p;
      if (seen++ % step == 0) samples.push_back(p);
    }
  }
  return {pointSetDiameter(samples), pointSetMinWidth(samples),
          sum / static_cast<float>(std::max<size_t>(1, seen))};
}

/// The pairs of distinct non-zero labels of `labels` within `reach` pixels of each other, each as
/// (smaller, larger).
std::set<std::pair<int, int>> touchingLabels(const cv::Mat& labels, int reach) {
  std::set<std::pair<int, int>> out;
  for (int v = 0; v < labels.rows; ++v) {
    for (int u = 0; u < labels.cols; ++u) {
      const int a = labels.at<int>(v, u);
      if (!a) continue;
      // The half of the neighbourhood below and to the right: each pair of pixels once.
      for (int dv = 0; dv <= reach && v + dv < labels.rows; ++dv) {
        for (int du = dv == 0 ? 1 : -reach; du <= reach; ++du) {
          if (u + du < 0 || u + du >= labels.cols) continue;
          const int b = labels.at<int>(v + dv, u + du);
          if (b && b != a) out.emplace(std::min(a, b), std::max(a, b));
        }
      }
    }
  }
  return out;
}

/// The full image's rectangle of a rectangle of the reduced one.
cv::Rect fullRect(const cv::Rect& box, int stride, cv::Size size) {
  return cv::Rect(box.tl() * stride, box.size() * stride) & cv::Rect(cv::Point(), size);
}

/// The full-size mask of the region with `label` in the reduced `labels`: its pixels, each grown to
/// the stride's block, where the full image has depth.
cv::Mat fullMask(const cv::Mat& labels, int label, const cv::Rect& box, int stride,
                 const cv::Mat& valid) {
  cv::Mat mask(valid.size(), CV_8UC1, cv::Scalar(0));
  const cv::Rect full = fullRect(box, stride, valid.size());
  cv::Mat reduced = labels(box) == label, grown;
  cv::resize(reduced, grown, {box.width * stride, box.height * stride}, 0, 0, cv::INTER_NEAREST);
  grown(cv::Rect(0, 0, full.width, full.height)).copyTo(mask(full), valid(full));
  return mask;
}

/// A reduced-size mask brought to the full image, each pixel to its stride's block.
cv::Mat fullSize(const cv::Mat& reduced, int stride, cv::Size size) {
  cv::Mat grown;
  cv::resize(reduced, grown, reduced.size() * stride, 0, 0, cv::INTER_NEAREST);
  return grown(cv::Rect(0, 0, size.width, size.height)).clone();
}

/// Adds a region (`mask`, CV_8UC1 of the image's size, inside `box`) to `map` (CV_32FC1), softened
/// as segmentation_inputs.h softens a mask of `score`: within its box and the blur's reach only,
/// which is all the blur changes.
void addSoftRegion(const cv::Mat& mask, const cv::Rect& box, float score,
                   const GeometricSegmentationParams& params, cv::Mat& map) {
  SegmentationInputParams soft;
  soft.mask_border_px = params.border_px;
  soft.mask_inside_floor = params.inside_floor;
  soft.mask_outside_floor = params.outside_floor;
  const int reach = static_cast<int>(std::ceil(4 * params.border_px)) + 1;
  const cv::Rect roi = (box + cv::Size(2 * reach, 2 * reach) - cv::Point(reach, reach)) &
                       cv::Rect(cv::Point(), map.size());
  const cv::Mat part = maskProbability({InstanceMask{mask(roi), 0, score}}, 0, roi.size(), soft);
  cv::Mat target = map(roi);
  cv::max(target, part, target);
}

/// How well a region's extent matches an object's expected visible extent (kVisibleShare of its
/// diameter), in (0, 1]: a log-normal bell of deviation size_sigma.
float sizeScore(float extent, const ObjectSize& size, const GeometricSegmentationParams& params) {
  const float z = std::log(extent / (kVisibleShare * size.diameter)) / params.size_sigma;
  return std::exp(-0.5f * z * z);
}

/// Whether a candidate of this extent and thinnest width can hold an object of `size` (regionFits).
bool extentFits(float extent, float min_width, const ObjectSize& size,
                const GeometricSegmentationParams& params) {
  return extent >= params.min_extent_share * size.diameter &&
         extent <= params.max_extent_share * size.diameter &&
         min_width <= params.max_extent_share * size.min_width + params.width_margin;
}

/// A candidate's score for an object of `size` (0 when it cannot hold it): its size score, scaled
/// by how its colours meet the object's `colours` where both have colour.
float candidateScore(float extent, float min_width, const ChromaticityHistogram& region_colours,
                     const ObjectSize& size, const GeometricSegmentationParams& params,
                     const ChromaticityHistogram* colours) {
  if (!extentFits(extent, min_width, size, params)) return 0;
  float score = sizeScore(extent, size, params);
  if (colours && colours->samples() > 0 && region_colours.samples() > 0) {
    score *= 1 - params.colour_weight + params.colour_weight * region_colours.overlap(*colours);
  }
  return score;
}

}  // namespace

/// PCL's estimators, kept with their buffers from frame to frame.
struct GeometricSegmenter::Pcl {
  pcl::IntegralImageNormalEstimation<pcl::PointXYZ, pcl::Normal> normals;
  pcl::OrganizedMultiPlaneSegmentation<pcl::PointXYZ, pcl::Normal, pcl::Label> planes;
  pcl::OrganizedEdgeBase<pcl::PointXYZ, pcl::Label> edges;
};

/// One frame's work at the reduced resolution.
class ReducedFrame {
 public:
  ReducedFrame(GeometricSegmenter::Pcl& pcl, const GeometricSegmentationParams& params,
               const OrganizedCloud& cloud, const CameraIntrinsics& camera)
      : pcl_(pcl),
        params_(params),
        stride_(params.stride),
        cloud_(reducedCloud(cloud, stride_)),
        camera_(reducedCamera(camera, stride_, static_cast<int>(cloud_->width),
                              static_cast<int>(cloud_->height))),
        normals_(new PclNormals) {}

  GeometricSegmentation segment(const OrganizedCloud& full) {
    estimateNormals();
    GeometricSegmentation out;
    const cv::Mat planes = supportingPlanes(out.planes);
    const cv::Mat edges = edgeMask();
    cv::Mat valid(camera_.height, camera_.width, CV_8UC1);
    for (size_t i = 0; i < cloud_->size(); ++i) {
      valid.data[i] = std::isfinite((*cloud_)[i].z) ? 255 : 0;
    }
    const cv::Size size(full.width, full.height);
    out.plane_mask = fullSize(planes, stride_, size);
    out.edge_mask = fullSize(edges, stride_, size);
    regions(valid & ~planes & ~edges, valid & ~planes, validMask(full), out);
    return out;
  }

 private:
  void estimateNormals() {
    auto& estimation = pcl_.normals;
    estimation.setNormalEstimationMethod(estimation.AVERAGE_3D_GRADIENT);
    // PCL's step limit is factor * 2 (z + 1): a quarter of the share matches it at z = 1 m.
    estimation.setMaxDepthChangeFactor(params_.depth_discontinuity / 4.0f);
    estimation.setNormalSmoothingSize(static_cast<float>(smoothing()));
    estimation.setInputCloud(cloud_);
    estimation.compute(*normals_);
  }

  /// CV_8UC1 mask of every plane of at least the params' area, and how many there were.
  cv::Mat supportingPlanes(int& count) {
    auto& segmentation = pcl_.planes;
    segmentation.setInputCloud(cloud_);
    segmentation.setInputNormals(normals_);
    segmentation.setMinInliers(static_cast<unsigned>(minPixels()));
    segmentation.setAngularThreshold(radians(params_.plane_angle_deg));
    segmentation.setDistanceThreshold(kPlaneGrowDistance);
    segmentation.setMaximumCurvature(kPlaneMaxCurvature);
    std::vector<pcl::ModelCoefficients> coefficients;
    std::vector<pcl::PointIndices> inliers;
    segmentation.segment(coefficients, inliers);
    cv::Mat mask(camera_.height, camera_.width, CV_8UC1, cv::Scalar(0));
    count = 0;
    for (size_t k = 0; k < coefficients.size(); ++k) {
      if (alreadyRemoved(inliers[k], mask)) continue;
      const auto& c = coefficients[k].values;
      const auto plane = supportingPlane({c[0], c[1], c[2], c[3]}, inliers[k]);
      if (!plane) continue;
      markPlane(OnPlane(*cloud_, *normals_, *plane, params_.plane_distance), mask);
      ++count;
    }
    return mask;
  }

  /// Whether most of a plane segment lies on a supporting plane already removed (another segment
  /// of a table that noise broke up).
  static bool alreadyRemoved(const pcl::PointIndices& segment, const cv::Mat& mask) {
    size_t on = 0;
    for (const int i : segment.indices) on += mask.data[i] != 0;
    return 2 * on > segment.indices.size();
  }

  /// The supporting plane a PCL plane segment lies on, if the surface it spreads over has the
  /// params' area. PCL fits the plane to the segment alone, which a noisy sensor tilts: while the
  /// surface is smaller, the plane is fitted again to it (kPlaneRefits times).
  std::optional<Eigen::Vector4f> supportingPlane(Eigen::Vector4f plane,
                                                 const pcl::PointIndices& segment) const {
    pcl::PointIndices surface = segment;
    for (int pass = 0;; ++pass) {
      const OnPlane on_plane(*cloud_, *normals_, plane, params_.plane_distance);
      surface = spreadSurface(on_plane, camera_.width, camera_.height, surface);
      if (planeArea(*cloud_, camera_, surface, plane.head<3>()) >= params_.plane_min_area) {
        return plane;
      }
      if (pass == kPlaneRefits || surface.indices.size() < 3) return std::nullopt;
      float curvature = 0;  // the least-squares plane of the surface
      pcl::computePointNormal(*cloud_, surface.indices, plane, curvature);
    }
  }

  /// CV_8UC1 mask of the depth-discontinuity and crease edges, widened by the params.
  cv::Mat edgeMask() {
    auto& edges = pcl_.edges;
    edges.setEdgeType(edges.EDGELABEL_OCCLUDING | edges.EDGELABEL_OCCLUDED);
    edges.setDepthDisconThreshold(params_.depth_discontinuity);
    edges.setMaxSearchNeighbors(kEdgeSearchNeighbours);
    edges.setInputCloud(cloud_);
    PclLabels labels;
    std::vector<pcl::PointIndices> indices;
    edges.compute(labels, indices);
    cv::Mat mask(camera_.height, camera_.width, CV_8UC1, cv::Scalar(0));
    for (const auto& kind : indices) {
      for (const int i : kind.indices) mask.data[i] = 255;
    }
    markCreases(*cloud_, *normals_, params_.crease_angle_deg, smoothing(), mask);
    const int dilation = (params_.edge_dilation_px + stride_ - 1) / stride_;
    if (dilation > 0) {
      const int k = 2 * dilation + 1;
      cv::dilate(mask, mask, cv::getStructuringElement(cv::MORPH_RECT, {k, k}));
    }
    return mask;
  }

  /// The connected regions of `free` of at least the params' size, grown back over the edges
  /// into `grow`, largest first, their masks brought to the full image where it is `valid`; and
  /// the pairs of them that touch.
  void regions(const cv::Mat& free, const cv::Mat& grow, const cv::Mat& valid,
               GeometricSegmentation& out) const {
    cv::Mat labels = largeComponents(free);
    growIntoEdges(*cloud_, grow, params_.depth_discontinuity, smoothing(), labels);
    std::map<int, std::pair<cv::Rect, int>> boxes;  // per label: bounding box, pixels
    for (int v = 0; v < labels.rows; ++v) {
      for (int u = 0; u < labels.cols; ++u) {
        const int label = labels.at<int>(v, u);
        if (!label) continue;
        auto [it, fresh] = boxes.try_emplace(label, cv::Rect(u, v, 1, 1), 0);
        it->second.first |= cv::Rect(u, v, 1, 1);
        ++it->second.second;
      }
    }
    std::vector<std::pair<DepthRegion, int>> labelled;  // each region with its label
    for (const auto& [label, shape] : boxes) {
      const auto& [box, pixels] = shape;
      DepthRegion region;
      region.mask = fullMask(labels, label, box, stride_, valid);
      const cv::Rect full = fullRect(box, stride_, valid.size());
      region.box = cv::boundingRect(region.mask(full)) + full.tl();
      region.pixels = cv::countNonZero(region.mask(region.box));
      const RegionShape measured = measureShape(
          labels, [label = label](int l) { return l == label; }, box, pixels, *cloud_);
      region.extent = measured.extent;
      region.min_width = measured.min_width;
      region.centroid = measured.centroid;
      labelled.emplace_back(std::move(region), label);
    }
    std::sort(labelled.begin(), labelled.end(),
              [](const auto& a, const auto& b) { return a.first.pixels > b.first.pixels; });
    std::map<int, size_t> index;  // label -> index into out.regions
    for (auto& [region, label] : labelled) {
      index[label] = out.regions.size();
      out.regions.push_back(std::move(region));
    }
    const int reach = std::max(1, kTouchPx / stride_);
    for (const auto& [a, b] : touchingLabels(labels, reach)) {
      const cv::Rect box = boxes[a].first | boxes[b].first;
      const RegionShape measured = measureShape(
          labels, [a = a, b = b](int l) { return l == a || l == b; }, box,
          boxes[a].second + boxes[b].second, *cloud_);
      out.adjacent.push_back({std::min(index[a], index[b]), std::max(index[a], index[b]),
                              measured.extent, measured.min_width});
    }
  }

  /// The 4-connected components of `free` (CV_32S labels), those below the params' size as 0.
  cv::Mat largeComponents(const cv::Mat& free) const {
    cv::Mat labels, stats, centroids;
    const int count = cv::connectedComponentsWithStats(free, labels, stats, centroids, 4, CV_32S);
    std::vector<int> kept(count, 0);
    for (int label = 1; label < count; ++label) {
      kept[label] = stats.at<int>(label, cv::CC_STAT_AREA) >= minPixels() ? label : 0;
    }
    for (auto it = labels.begin<int>(); it != labels.end<int>(); ++it) *it = kept[*it];
    return labels;
  }

  static cv::Mat validMask(const OrganizedCloud& cloud) {
    cv::Mat valid(cloud.height, cloud.width, CV_8UC1);
    for (int i = 0; i < static_cast<int>(cloud.points.size()); ++i) {
      valid.data[i] = cloud.isValid(i) ? 255 : 0;
    }
    return valid;
  }

  /// normal_smoothing_px in reduced pixels.
  int smoothing() const {
    return std::max(2, static_cast<int>(std::lround(params_.normal_smoothing_px / stride_)));
  }

  /// min_region_px in reduced pixels.
  int minPixels() const { return std::max(1, params_.min_region_px / (stride_ * stride_)); }

  GeometricSegmenter::Pcl& pcl_;
  const GeometricSegmentationParams& params_;
  int stride_;
  PclCloud::Ptr cloud_;
  CameraIntrinsics camera_;
  PclNormals::Ptr normals_;
};

GeometricSegmenter::GeometricSegmenter(const GeometricSegmentationParams& params)
    : params_(params), pcl_(std::make_unique<Pcl>()) {
  params_.validate();
}

GeometricSegmenter::~GeometricSegmenter() = default;
GeometricSegmenter::GeometricSegmenter(GeometricSegmenter&&) noexcept = default;
GeometricSegmenter& GeometricSegmenter::operator=(GeometricSegmenter&&) noexcept = default;

GeometricSegmentation GeometricSegmenter::segment(const OrganizedCloud& cloud,
                                                  const CameraIntrinsics& camera) {
  checkInput(cloud, camera);
  return ReducedFrame(*pcl_, params_, cloud, camera).segment(cloud);
}

GeometricSegmentation GeometricSegmenter::segment(const cv::Mat& depth,
                                                  const CameraIntrinsics& camera,
                                                  double metres_per_unit) {
  return segment(cloudFromDepth(depth, camera, metres_per_unit), camera);
}

ObjectSize ObjectSize::of(const std::vector<Eigen::Vector3f>& points) {
  return {pointSetDiameter(points), pointSetMinWidth(points)};
}

bool regionFits(const DepthRegion& region, const ObjectSize& size,
                const GeometricSegmentationParams& params) {
  return extentFits(region.extent, region.min_width, size, params);
}

cv::Mat regionProbability(const GeometricSegmentation& segmentation, size_t region,
                          const GeometricSegmentationParams& params) {
  if (region >= segmentation.regions.size()) {
    throw InputError(fmt::format("region {} does not exist; the segmentation has {}", region,
                                 segmentation.regions.size()));
  }
  cv::Mat map(segmentation.plane_mask.size(), CV_32FC1, cv::Scalar(params.outside_floor));
  const DepthRegion& r = segmentation.regions[region];
  addSoftRegion(r.mask, r.box, 1.0f, params, map);
  return map;
}

void addRegionColours(GeometricSegmentation& segmentation, const cv::Mat& bgr) {
  if (bgr.type() != CV_8UC3 || bgr.size() != segmentation.plane_mask.size()) {
    throw InputError(fmt::format("colour image {}x{} (type {}) does not fit the {}x{} depth image",
                                 bgr.cols, bgr.rows, bgr.type(), segmentation.plane_mask.cols,
                                 segmentation.plane_mask.rows));
  }
  for (DepthRegion& region : segmentation.regions) {
    region.colours = ChromaticityHistogram::of(bgr(region.box), region.mask(region.box));
  }
}

cv::Mat objectProbability(const GeometricSegmentation& segmentation, const ObjectSize& size,
                          const GeometricSegmentationParams& params,
                          const ChromaticityHistogram* colours) {
  if (!(size.diameter > 0) || !std::isfinite(size.diameter)) {
    throw InputError(fmt::format("object diameter {} m is not finite and positive", size.diameter));
  }
  if (!(size.min_width >= 0) || !std::isfinite(size.min_width)) {
    throw InputError(
        fmt::format("object width {} m is not finite and non-negative", size.min_width));
  }
  cv::Mat map(segmentation.plane_mask.size(), CV_32FC1, cv::Scalar(params.outside_floor));
  std::vector<float> scores;
  for (const DepthRegion& region : segmentation.regions) {
    scores.push_back(
        candidateScore(region.extent, region.min_width, region.colours, size, params, colours));
    if (scores.back() > 0) {
      addSoftRegion(region.mask, region.box, std::max(params.min_region_score, scores.back()),
                    params, map);
    }
  }
  for (const AdjacentRegions& pair : segmentation.adjacent) {
    ChromaticityHistogram joined_colours = segmentation.regions[pair.first].colours;
    joined_colours += segmentation.regions[pair.second].colours;
    const float score =
        candidateScore(pair.extent, pair.min_width, joined_colours, size, params, colours);
    if (score >= params.min_region_score &&
        score > std::min(scores[pair.first], scores[pair.second])) {
      const DepthRegion& a = segmentation.regions[pair.first];
      const DepthRegion& b = segmentation.regions[pair.second];
      addSoftRegion(a.mask | b.mask, a.box | b.box, score, params, map);
    }
  }
  return map;
}

const ParamSet<GeometricSegmentationParams>& GeometricSegmentationParams::schema() {
  using P = GeometricSegmentationParams;
  static const ParamSet<P> schema =
      ParamSet<P>()
          .add(&P::stride, "stride", "px", ParamRange::closed(1, 8),
               "every this many pixels along each axis are segmented; 1: every pixel")
          .add(&P::normal_smoothing_px, "normal_smoothing_px", "px", ParamRange::closed(1, 100),
               "window of the integral-image normals (full-image pixels)")
          .add(&P::depth_discontinuity, "depth_discontinuity", "", ParamRange::aboveUpTo(0, 1),
               "a step larger than this share of the depth between neighbours is an edge")
          .add(&P::plane_min_area, "plane_min_area", "m^2", ParamRange::aboveUpTo(0, 100),
               "a plane of at least this area is a supporting surface and is removed")
          .add(&P::plane_angle_deg, "plane_angle_deg", "deg", ParamRange::aboveUpTo(0, 45),
               "neighbouring normals within this angle grow one plane")
          .add(&P::plane_distance, "plane_distance", "m", ParamRange::aboveUpTo(0, 0.1),
               "a point this close to a supporting plane (facing as it does) belongs to it")
          .add(&P::crease_angle_deg, "crease_angle_deg", "deg", ParamRange::closed(1, 180),
               "neighbours whose normals turn by more than this in a valley are an edge; 180: "
               "none")
          .add(&P::edge_dilation_px, "edge_dilation_px", "px", ParamRange::closed(0, 20),
               "edges are widened by this before the regions are grown")
          .add(&P::min_region_px, "min_region_px", "px", ParamRange::closed(1, 1000000),
               "a connected region of fewer pixels is not a candidate")
          .add(&P::min_extent_share, "min_extent_share", "", ParamRange::closed(0, 10),
               "a candidate holds an object when its extent is at least this share of the "
               "object's diameter")
          .add(&P::max_extent_share, "max_extent_share", "", ParamRange::aboveUpTo(0, 10),
               "... and at most this share, and its thinnest width at most this share of the "
               "object's plus width_margin")
          .add(&P::width_margin, "width_margin", "m", ParamRange::closed(0, 1),
               "what a candidate may be thicker than the object for the sensor's noise")
          .add(&P::size_sigma, "size_sigma", "", ParamRange::aboveUpTo(0, 10),
               "deviation of ln(extent / visible extent) of a candidate's score")
          .add(&P::colour_weight, "colour_weight", "", ParamRange::closed(0, 1),
               "share of a candidate's score that its colours meeting the object's decide")
          .add(&P::min_region_score, "min_region_score", "", ParamRange::closed(0, 1),
               "the least score of a candidate that can hold the object")
          .add(&P::border_px, "border_px", "px", ParamRange::closed(0, 100),
               "a candidate's border is blurred by a Gaussian of this deviation; 0: hard edges")
          .add(&P::inside_floor, "inside_floor", "", ParamRange::closed(0, 1),
               "a candidate's pixel keeps at least this probability after the blur")
          .add(&P::outside_floor, "outside_floor", "", ParamRange::fromBelow(0, 1),
               "every pixel gets at least this probability");
  return schema;
}

void GeometricSegmentationParams::validate() const {
  schema().validate(*this);
  if (min_extent_share >= max_extent_share) {
    throw InputError(fmt::format("min_extent_share {} must be below max_extent_share {}",
                                 min_extent_share, max_extent_share));
  }
}

}  // namespace stocs
