#pragma once
// What every baseline shares, so that they differ only in their own pose search: the hard segment
// (probability > MethodOptions::hard_threshold) from the same organized cloud, voxel size and
// normals as StoCS, the same model samples, the same minimum segment size, and afterwards the same
// refinement StoCS applies to its best pose (point-to-plane ICP on the segment, kept unless it
// lowers the alignment objective below 90%), switched by the same parameter (stocs.icp.enabled).

#include <Eigen/Geometry>
#include <optional>

#include "stocs/estimation/stages/soft_segment.h"
#include "stocs/methods/pose_method.h"

namespace stocs {

/// The pose a baseline's search settled on.
struct BaselineHypothesis {
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();  ///< model to camera, metres
  double score = 0;     ///< the method's own fitness, mapped so that higher is better
  long hypotheses = 0;  ///< hypotheses the method reports having verified (0: not reported)
};

class BaselineMethod : public PoseMethod {
 public:
  /// Segments with fewer points give no pose (a 4-point base needs 4, as in StoCS).
  static constexpr size_t kMinSegmentPoints = 4;

  explicit BaselineMethod(float hard_threshold) : threshold_(hard_threshold) {}

  /// Hard segment, search(), then the shared refinement. Throws InputError for invalid parameters
  /// or mismatched inputs; any other failure (empty or tiny segment, no pose, a non-finite pose)
  /// gives found = false.
  PoseEstimate estimate(const ObjectInput& input) final;

 protected:
  /// The method's own search on the hard segment (at least kMinSegmentPoints points); nothing
  /// when it finds no pose.
  virtual std::optional<BaselineHypothesis> search(const SoftSegment& segment,
                                                   const ObjectInput& input) = 0;

 private:
  float threshold_;
};

}  // namespace stocs
