#pragma once
// Every error metric of one estimate of one object against the ground-truth instances of that
// object in the image (units: mm and degrees, as BOP).
//
// The estimate is compared with the nearest instance, the one with the smallest ADD-S, so that in
// a bin of identical objects any instance counts; every metric of the target is measured against
// that instance. A missing estimate has infinite errors and fails every criterion.

#include <vector>

#include "stocs/eval/pose_metrics.h"
#include "stocs/io/bop_dataset.h"

namespace stocs {

struct TargetErrors {
  bool found = false;
  int instance = -1;      ///< index of the matched instance in the list given; -1 when missing
  double add_mm;          ///< ADD against the matched instance
  double adds_mm;         ///< ADD-S (closest model point), for every object
  double mssd_mm;         ///< BOP's MSSD (pose_metrics.h) under models_info's symmetries
  double rotation_deg;    ///< mean absolute roll, pitch, yaw error, nearest symmetric pose
  double translation_mm;  ///< of that same symmetric pose
  double diameter_mm = 0;
  bool symmetric = false;  ///< models_info lists a symmetry

  TargetErrors();  ///< a missing estimate: infinite errors

  /// ADD(-S): ADD-S for objects models_info marks symmetric, ADD otherwise.
  double addOrAddsMm() const { return symmetric ? adds_mm : add_mm; }
  /// ADD-S below 10% of the diameter.
  bool addsSuccess() const { return adds_mm < 0.1 * diameter_mm; }
  /// ADD(-S) below 10% of the diameter.
  bool addOrAddsSuccess() const { return addOrAddsMm() < 0.1 * diameter_mm; }
  /// MSSD below `share` of the diameter (BOP's correctness at threshold `share`).
  bool mssdSuccess(double share = 0.1) const { return mssd_mm < share * diameter_mm; }
  /// BOP's recall of MSSD averaged over the thresholds 0.05, 0.1, ..., 0.5 of the diameter for
  /// this target: the share of those thresholds its MSSD is below.
  double mssdRecall() const;
  /// The paper's APC criterion: rotation error below 10 degrees and translation error below 2 cm.
  bool rtSuccess() const { return rotation_deg < 10 && translation_mm < 20; }
};

class ObjectMetrics {
 public:
  static constexpr size_t kMssdPoints = 2000;

  /// `points_mm`: the model's points (every vertex of the model file, in mm); `info`: its
  /// models_info entry. The diameter is the entry's, else that of the points. MSSD takes at most
  /// kMssdPoints of the points, evenly spaced in their order. Throws InputError for an empty model
  /// or an invalid symmetry.
  ObjectMetrics(std::vector<Eigen::Vector3f> points_mm, const BopObjectInfo& info);

  /// Errors of `estimate` (nullptr: missing) against the nearest of `instances` (poses in mm).
  /// Throws InputError when `instances` is empty.
  TargetErrors evaluate(const RigidPose* estimate, const std::vector<RigidPose>& instances) const;

  double diameterMm() const { return diameter_mm_; }

 private:
  AddsMetric adds_;
  std::vector<Eigen::Vector3f> mssd_points_;
  Eigen::Vector3d centroid_;
  std::vector<RigidPose> symmetries_;
  double diameter_mm_;
  bool symmetric_;
};

}  // namespace stocs
