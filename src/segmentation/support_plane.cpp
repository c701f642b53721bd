#include "stocs/segmentation/support_plane.h"

#include <pcl/point_types.h>
#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_plane.h>

#include <cmath>
#include <memory>

namespace stocs {
namespace {

/// RANSAC's draws: enough for a plane holding a third of the points (0.99 sure after 170).
constexpr int kIterations = 200;

}  // namespace

std::optional<Plane> dominantPlane(const std::vector<Eigen::Vector3f>& points, float tolerance,
                                   size_t min_inliers) {
  if (points.size() < std::max<size_t>(3, min_inliers)) return std::nullopt;
  // Made here with std::allocator, not PCL's aligned operator new: built for another language
  // standard, PCL's library and this file would allocate and free them differently (ASan).
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  cloud->reserve(points.size());
  for (const Eigen::Vector3f& p : points) cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  auto model = std::make_shared<pcl::SampleConsensusModelPlane<pcl::PointXYZ>>(cloud);
  pcl::RandomSampleConsensus<pcl::PointXYZ> ransac(model, tolerance);
  ransac.setMaxIterations(kIterations);
  if (!ransac.computeModel()) return std::nullopt;
  pcl::Indices inliers;
  ransac.getInliers(inliers);
  if (inliers.size() < min_inliers) return std::nullopt;
  Eigen::VectorXf coefficients, refined;
  ransac.getModelCoefficients(coefficients);
  model->optimizeModelCoefficients(inliers, coefficients, refined);
  if (refined.size() != 4) return std::nullopt;
  Plane plane;
  plane.normal = refined.head<3>();
  const float norm = plane.normal.norm();
  if (!(norm > 0) || !std::isfinite(norm)) return std::nullopt;
  plane.normal /= norm;
  plane.offset = refined[3] / norm;
  if (plane.offset < 0) {  // the camera, at the origin, on the positive side
    plane.normal = -plane.normal;
    plane.offset = -plane.offset;
  }
  return plane;
}

}  // namespace stocs
