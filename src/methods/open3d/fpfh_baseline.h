#pragma once
// What the two Open3D baselines (o3d-ransac, o3d-fgr) share: the clouds and FPFH features of
// Open3D's global registration tutorial, built from the model samples (the source) and the hard
// segment (the target), so that the transformation found maps the model into the camera frame;
// the run's seed and thread count given to Open3D. Parameters and their sources: fpfh_baseline.cpp.
// A private header of stocs_methods_open3d: Open3D's headers go no further.

#include <open3d/geometry/PointCloud.h>
#include <open3d/pipelines/registration/Feature.h>
#include <open3d/pipelines/registration/Registration.h>

#include <memory>

#include "baseline_method.h"

namespace stocs {

/// The two clouds of a registration at one resolution, with their FPFH features.
struct FpfhClouds {
  double voxel_size = 0;                 ///< metres: the tutorial's voxel_size
  open3d::geometry::PointCloud model;    ///< source: the model samples with their normals
  open3d::geometry::PointCloud segment;  ///< target: the hard segment with its normals
  std::shared_ptr<open3d::pipelines::registration::Feature> model_features;
  std::shared_ptr<open3d::pipelines::registration::Feature> segment_features;
};

/// The clouds and FPFH features of `segment` and `model`; `segment_voxel_size` is the size the
/// segment's points were voxelised at (SoftSegmentParams::voxel_size).
FpfhClouds fpfhClouds(const SoftSegment& segment, const ObjectModel& model,
                      float segment_voxel_size);

/// A baseline that registers the model to the hard segment by FPFH feature matching with Open3D.
class FpfhBaselineMethod : public BaselineMethod {
 public:
  using BaselineMethod::BaselineMethod;

 protected:
  /// fpfhClouds(), then align() with Open3D's random engine seeded from the run's seed and its
  /// OpenMP threads set to the run's; the pose with score = Open3D's fitness (the share of model
  /// samples with a segment point within the method's correspondence distance), or nothing when
  /// the fitness is 0 (Open3D found no transformation).
  std::optional<BaselineHypothesis> search(const SoftSegment& segment,
                                           const ObjectInput& input) final;

  /// The method's own registration of clouds.model onto clouds.segment.
  virtual open3d::pipelines::registration::RegistrationResult align(
      const FpfhClouds& clouds) const = 0;
};

}  // namespace stocs
