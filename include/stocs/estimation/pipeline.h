#pragma once
// The per-object step of a frame's estimation (estimateFrame, frame.h): the object's soft segment,
// the StoCS search on it (StocsEstimator::search) and each pose judged; and every parameter of it.

#include "stocs/estimation/stages/frame_explanation.h"
#include "stocs/estimation/stages/free_space_check.h"
#include "stocs/estimation/stages/pose_confidence.h"
#include "stocs/estimation/stages/soft_segment.h"
#include "stocs/estimation/stocs_estimator.h"
#include "stocs/geometry/camera.h"
#include "stocs/geometry/organized_cloud.h"
#include "stocs/model/model_cache.h"
#include "stocs/segmentation/colour_boundaries.h"
#include "stocs/util/param_set.h"

namespace cv {
class Mat;
}

namespace stocs {

/// Every parameter of the estimation, grouped by stage.
struct PipelineParams {
  SoftSegmentParams segment;
  ModelPreparationParams model;
  StocsParams stocs;
  ConfidenceParams confidence;
  FrameExplanationParams explanation;      ///< after every object of a frame (estimateFrame)
  ColourBoundaryParams colour_boundaries;  ///< instance boundaries where a frame has no map of them

  /// Key, range, unit and meaning of every field (docs/parameters.md).
  static const ParamSet<PipelineParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
};

/// Segments the cloud with `probability` (CV_32FC1, see toProbabilityImage), splits it into
/// instance regions (see labelRegions) with `boundary_map`, or without one with a map from `colour`
/// when the search is for several instances (ColourBoundaryParams), and runs StoCS. `camera`, the
/// cloud's intrinsics for the free-space check, is recovered from the cloud when null (a caller
/// estimating several objects of a frame passes it once known). The estimate's seconds and stages
/// include the soft segment. Every instance gets its confidence evidence, confidence and verdict
/// (judgePose). Throws InputError on size or type mismatches.
PoseEstimate detectObject(const OrganizedCloud& cloud, float focal_px, const cv::Mat& probability,
                          const PreparedModel& model, const PipelineParams& params,
                          const cv::Mat* boundary_map = nullptr,
                          const CameraIntrinsics* camera = nullptr,
                          const cv::Mat* colour = nullptr);

/// detectObject after its soft segment: StoCS on `segment` (of `cloud` and `probability`), each
/// instance turned to its canonical equivalent under the model's declared symmetries
/// (canonicalPose) and judged (judgeInstance). `colour` (optional CV_8UC3 BGR registered with the
/// cloud) helps tell a pose from its shape alternatives. Leaves the estimate's segment time and
/// `seconds` to the caller.
PoseEstimate detectOnSegment(const SoftSegment& segment, const OrganizedCloud& cloud,
                             const cv::Mat& probability, const PreparedModel& model,
                             const PipelineParams& params, const CameraIntrinsics* camera,
                             const cv::Mat* colour = nullptr);

/// The confidence evidence of `pose` that needs the frame (its `lcp` must be set; see
/// ConfidenceEvidence; consensus is left as it is), then its verdict (judgePose). Without
/// `surface` (no camera) nothing confirms a pose.
void judgeInstance(InstancePose& pose, const ObjectModel& model, const FreeSpaceCheck* surface,
                   const cv::Mat& probability, const ConfidenceParams& params);

}  // namespace stocs
