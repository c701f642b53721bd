#include "stocs/estimation/pipeline.h"

#include <omp.h>

#include <chrono>
#include <optional>

#include "stocs/estimation/free_space_check.h"
#include "stocs/util/error.h"

namespace stocs {

const ParamSet<PipelineParams>& PipelineParams::schema() {
  static const ParamSet<PipelineParams> schema =
      ParamSet<PipelineParams>()
          .nest(&PipelineParams::segment, "segment", SoftSegmentParams::schema(),
                "Soft segment (paper eqs. 1-3)")
          .nest(&PipelineParams::model, "model", ModelPreparationParams::schema(),
                "Model preparation")
          .nest(&PipelineParams::stocs, "stocs", StocsParams::schema(), "StoCS (paper section 3)");
  return schema;
}

void PipelineParams::validate() const {
  schema().validate(*this);
}

PoseEstimate estimateObject(const OrganizedCloud& cloud, float focal_px, const cv::Mat& probability,
                            const PreparedModel& model, const PipelineParams& params,
                            const cv::Mat* boundary_map, const CameraIntrinsics* camera) {
  const auto start = std::chrono::steady_clock::now();
  const int threads = params.stocs.threads > 0 ? params.stocs.threads : omp_get_max_threads();
  SoftSegment segment = buildSoftSegment(cloud, probability, focal_px, params.segment, threads);
  if (boundary_map) labelRegions(segment, *boundary_map, cloud.width, cloud.height);
  const double segment_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::optional<CameraIntrinsics> recovered;  // the free-space check keeps a reference
  if (params.stocs.free_space.enabled && !camera) {
    try {
      recovered = intrinsicsFromCloud(cloud);
      camera = &*recovered;
    } catch (const InputError&) {
      // Too few valid points to recover the camera: nothing is known about free space either.
    }
  }
  std::optional<FreeSpaceCheck> free_space;
  if (params.stocs.free_space.enabled && camera) {
    free_space.emplace(cloud, *camera, params.stocs.free_space);
  }
  PoseEstimate result =
      StocsEstimator(model, params.stocs).estimate(segment, free_space ? &*free_space : nullptr);
  result.segment_points = segment.size();
  result.stages.segment = segment_seconds;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace stocs
