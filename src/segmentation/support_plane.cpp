#include "stocs/segmentation/support_plane.h"

#include <pcl/ModelCoefficients.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/segmentation/sac_segmentation.h>

#include <cmath>

namespace stocs {
namespace {

/// RANSAC's draws: enough for a plane holding a third of the points (0.99 sure after 170).
constexpr int kIterations = 200;

}  // namespace

std::optional<Plane> dominantPlane(const std::vector<Eigen::Vector3f>& points, float tolerance,
                                   size_t min_inliers) {
  if (points.size() < std::max<size_t>(3, min_inliers)) return std::nullopt;
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->reserve(points.size());
  for (const Eigen::Vector3f& p : points) cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  pcl::SACSegmentation<pcl::PointXYZ> ransac;
  ransac.setModelType(pcl::SACMODEL_PLANE);
  ransac.setMethodType(pcl::SAC_RANSAC);
  ransac.setDistanceThreshold(tolerance);
  ransac.setMaxIterations(kIterations);
  ransac.setOptimizeCoefficients(true);
  ransac.setInputCloud(cloud);
  pcl::PointIndices inliers;
  pcl::ModelCoefficients coefficients;
  ransac.segment(inliers, coefficients);
  if (inliers.indices.size() < min_inliers || coefficients.values.size() != 4) return std::nullopt;
  Plane plane;
  plane.normal =
      Eigen::Vector3f(coefficients.values[0], coefficients.values[1], coefficients.values[2]);
  const float norm = plane.normal.norm();
  if (!(norm > 0) || !std::isfinite(norm)) return std::nullopt;
  plane.normal /= norm;
  plane.offset = coefficients.values[3] / norm;
  if (plane.offset < 0) {  // the camera, at the origin, on the positive side
    plane.normal = -plane.normal;
    plane.offset = -plane.offset;
  }
  return plane;
}

}  // namespace stocs
