#pragma once
// What `stocs estimate --per-object FILE` records for every (image, object) it attempts, found or
// not: the method's own time for the object, which BOP results (one time per image) cannot hold,
// and the first pose's confidence evidence and confidence, which `stocs calibrate` fits.
// CSV: scene_id,im_id,obj_id,found,seconds,cpu_seconds,segment_points,hypotheses, then the
// evidence (ConfidenceEvidence::names()), confidence, and the first pose's 6x6 covariance
// (InstancePose::covariance), 36 blank-separated numbers row by row (zeros when nothing was found
// or the method gives none).

#include <Eigen/Core>
#include <filesystem>
#include <vector>

#include "stocs/estimation/stages/pose_confidence.h"
#include "stocs/eval/dataset_evaluation.h"

namespace stocs::tools {

struct ObjectRun {
  Target target;
  bool found = false;
  double seconds = 0;  ///< wall time of the method's estimate() for this object
  /// CPU time of the process (all its threads) during that estimate(): unlike wall time, not
  /// inflated by other processes on a shared machine.
  double cpu_seconds = 0;
  size_t segment_points = 0;
  long hypotheses = 0;
  ConfidenceEvidence evidence;  ///< of the first pose (zero when none)
  float confidence = 0;         ///< of the first pose (zero when none)
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
};

void writeObjectRuns(const std::filesystem::path& file, const std::vector<ObjectRun>& runs);

/// Throws InputError naming the file and line of a malformed row.
std::vector<ObjectRun> readObjectRuns(const std::filesystem::path& file);

}  // namespace stocs::tools
