#include "stocs/estimation/pipeline.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <optional>

#include "stocs/estimation/stages/free_space_check.h"
#include "stocs/segmentation/colour_boundaries.h"
#include "stocs/util/error.h"

namespace stocs {

const ParamSet<PipelineParams>& PipelineParams::schema() {
  static const ParamSet<PipelineParams> schema =
      ParamSet<PipelineParams>()
          .nest(&PipelineParams::segment, "segment", SoftSegmentParams::schema(),
                "Soft segment (paper eqs. 1-3)")
          .nest(&PipelineParams::model, "model", ModelPreparationParams::schema(),
                "Model preparation")
          .nest(&PipelineParams::stocs, "stocs", StocsParams::schema(), "StoCS (paper section 3)")
          .nest(&PipelineParams::confidence, "confidence", ConfidenceParams::schema(),
                "Confidence and rejection (docs/confidence.md)")
          .nest(&PipelineParams::explanation, "explanation", FrameExplanationParams::schema(),
                "Frame-level explanation (docs/confidence.md)")
          .nest(&PipelineParams::colour_boundaries, "colour_boundaries",
                ColourBoundaryParams::schema(),
                "Instance boundaries from the colour image (docs/algorithm.md)");
  return schema;
}

void PipelineParams::validate() const {
  schema().validate(*this);
}

void judgeInstance(InstancePose& pose, const ObjectModel& model, const FreeSpaceCheck* surface,
                   const cv::Mat& probability, const ConfidenceParams& params) {
  ConfidenceEvidence& e = pose.evidence;
  e.explained = 0;  // judged alone; the frame explanation sets it
  if (pose.lcp.facing > 0) {
    e.matched = std::min(1.0f, static_cast<float>(pose.lcp.matched) / pose.lcp.facing);
  }
  const SurfaceComparison c =
      surface ? surface->compare(model, pose.pose, &probability) : SurfaceComparison{};
  if (c.seen > 0) {
    e.surface_confirmed = static_cast<float>(c.confirmed) / static_cast<float>(c.seen);
    e.free_space = static_cast<float>(c.free) / static_cast<float>(c.seen);
  }
  if (c.confirmed > 0) {
    e.map_support = static_cast<float>(c.support / c.confirmed);
  }
  judgePose(pose, params);
}

PoseEstimate detectOnSegment(const SoftSegment& segment, const OrganizedCloud& cloud,
                             const cv::Mat& probability, const PreparedModel& model,
                             const PipelineParams& params, const CameraIntrinsics* camera,
                             const cv::Mat* colour) {
  std::optional<CameraIntrinsics> recovered;  // the free-space check keeps a reference
  if (!camera) {                              // also for the confidence evidence
    try {
      recovered = intrinsicsFromCloud(cloud);
      camera = &*recovered;
    } catch (const InputError&) {
      // Too few valid points to recover the camera: nothing is known about free space either.
    }
  }
  std::optional<FreeSpaceCheck> surface;  // ranks candidates when enabled, always gives evidence
  if (camera) surface.emplace(cloud, *camera, params.stocs.free_space);
  const bool rank_by_free_space = surface && params.stocs.free_space.enabled;
  const FrameEvidence evidence{surface ? &*surface : nullptr, colour};
  PoseEstimate result = StocsEstimator(model, params.stocs)
                            .search(segment, rank_by_free_space ? &*surface : nullptr, evidence);
  for (InstancePose& pose : result.instances) {
    pose.pose = canonicalPose(pose.pose, model.symmetries);
    judgeInstance(pose, model.model, evidence.surface, probability, params.confidence);
  }
  result.segment_points = segment.size();
  return result;
}

PoseEstimate detectObject(const OrganizedCloud& cloud, float focal_px, const cv::Mat& probability,
                          const PreparedModel& model, const PipelineParams& params,
                          const cv::Mat* boundary_map, const CameraIntrinsics* camera,
                          const cv::Mat* colour) {
  const auto start = std::chrono::steady_clock::now();
  const int threads = params.stocs.threads > 0 ? params.stocs.threads : omp_get_max_threads();
  SoftSegment segment = buildSoftSegment(cloud, probability, focal_px, params.segment, threads);
  cv::Mat from_colour;
  if (!boundary_map && colour && params.colour_boundaries.appliesTo(params.stocs.instances)) {
    from_colour = colourBoundaryMap(*colour, probability, params.colour_boundaries);
    boundary_map = &from_colour;
  }
  if (boundary_map) labelRegions(segment, *boundary_map, cloud.width, cloud.height);
  const double segment_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  PoseEstimate result = detectOnSegment(segment, cloud, probability, model, params, camera, colour);
  result.stages.segment = segment_seconds;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace stocs
