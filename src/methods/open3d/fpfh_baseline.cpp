// The clouds and features of both Open3D baselines, as Open3D's global registration tutorial
// (docs/jupyter/pipelines/global_registration.ipynb of Open3D 0.16, preprocess_point_cloud) makes
// them, with the inputs every baseline shares:
//   voxel size     the resolution both clouds already have: max(segment voxel size, model
//                  sampling radius); the model's is 4% of its diameter, so the size follows the
//                  object. The tutorial downsamples both clouds with it; the model samples are
//                  at it already, the hard segment is brought to it with VoxelDownSample when the
//                  model's is the coarser (else its voxel centroids are kept as they are).
//   normals        given, the same as StoCS's (the tutorial estimates them within 2 x voxel size;
//                  the segment's PCA normals use 1 cm, 2 x its 5 mm voxels)
//   FPFH           ComputeFPFHFeature within 5 x voxel size, at most 100 neighbours (the tutorial)
//   seed           Open3D 0.16's RANSAC takes no seed argument: it draws from Open3D's global
//                  engine (utility::random), seeded here from the run's seed before every search.
//                  FGR takes no seed either (its poses did not change with the seed in the tests).
//   threads        Open3D's loops (FPFH, feature matching, RANSAC's hypotheses) are OpenMP loops,
//                  run on the run's threads (0: all cores). RANSAC's threads draw from the one
//                  engine in whatever order they reach it, so only at --threads 1 is a seed sure
//                  to give the same pose every time.
#include "fpfh_baseline.h"

#include <omp.h>

#include <open3d/geometry/KDTreeSearchParam.h>
#include <open3d/utility/Random.h>

#include <algorithm>

#include "stocs/util/random.h"

namespace stocs {
namespace {

namespace reg = open3d::pipelines::registration;

constexpr double kFeatureRadius = 5.0;  // x voxel size
constexpr int kFeatureNeighbours = 100;

/// Open3D's OpenMP thread count for the lifetime of the object (0: left as it is); the previous
/// count is restored afterwards, so that nothing else in the process runs on a changed count.
class OpenMpThreads {
 public:
  explicit OpenMpThreads(int threads) : previous_(omp_get_max_threads()) {
    if (threads > 0) omp_set_num_threads(threads);
  }
  ~OpenMpThreads() { omp_set_num_threads(previous_); }
  OpenMpThreads(const OpenMpThreads&) = delete;
  OpenMpThreads& operator=(const OpenMpThreads&) = delete;

 private:
  int previous_;
};

open3d::geometry::PointCloud toOpen3d(const std::vector<Eigen::Vector3f>& points,
                                      const std::vector<Eigen::Vector3f>& normals) {
  open3d::geometry::PointCloud cloud;
  cloud.points_.reserve(points.size());
  cloud.normals_.reserve(normals.size());
  for (const Eigen::Vector3f& p : points) cloud.points_.push_back(p.cast<double>());
  for (const Eigen::Vector3f& n : normals) cloud.normals_.push_back(n.cast<double>());
  return cloud;
}

}  // namespace

FpfhClouds fpfhClouds(const SoftSegment& segment, const ObjectModel& model,
                      float segment_voxel_size) {
  FpfhClouds c;
  c.voxel_size = std::max(segment_voxel_size, model.sampling_radius);
  c.model = toOpen3d(model.points, model.normals);
  c.segment = toOpen3d(segment.points, segment.normals);
  if (c.voxel_size > segment_voxel_size) {
    // Averaged normals, made unit again: FPFH reads angles from them.
    c.segment = *c.segment.VoxelDownSample(c.voxel_size);
    c.segment.NormalizeNormals();
  }
  const open3d::geometry::KDTreeSearchParamHybrid features(kFeatureRadius * c.voxel_size,
                                                           kFeatureNeighbours);
  c.model_features = reg::ComputeFPFHFeature(c.model, features);
  c.segment_features = reg::ComputeFPFHFeature(c.segment, features);
  return c;
}

std::optional<BaselineHypothesis> FpfhBaselineMethod::search(const SoftSegment& segment,
                                                             const ObjectInput& input) {
  const StocsParams& params = input.params->stocs;
  const OpenMpThreads threads(params.threads);
  // Open3D takes an int seed; any 31 bits of the run's stream do.
  open3d::utility::random::Seed(static_cast<int>(streamSeed(params.seed, 0) & 0x7fffffff));
  const reg::RegistrationResult r =
      align(fpfhClouds(segment, input.model->model, input.params->segment.voxel_size));
  if (!(r.fitness_ > 0)) return std::nullopt;
  BaselineHypothesis h;
  h.pose.matrix() = r.transformation_.cast<float>();
  h.score = r.fitness_;
  return h;
}

}  // namespace stocs
