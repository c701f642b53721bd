#pragma once
// The confidence of a pose: the probability that it is right (ADD-S below 10% of the object's
// diameter), a logistic model over evidence that does not grow with the segment. The objective
// (LCP score) sums probability over the segment, so a large segment of the wrong object can
// outscore a small one of the right object; the shares below compare alike across objects,
// sensors and segment sizes. Coefficients come from `stocs calibrate` (docs/confidence.md).

#include <Eigen/Core>
#include <array>
#include <string>

#include "stocs/util/param_set.h"

namespace stocs {

struct InstancePose;

/// What the data says about one pose, each a share or a ratio, not a count.
struct ConfidenceEvidence {
  /// Of the model samples that face the camera under the pose and project onto a measured pixel,
  /// the share whose measured depth agrees within the free-space margin (the surface is there).
  float surface_confirmed = 0;
  /// Of the same samples, the share in front of the measured depth (where the sensor sees
  /// through): FreeSpaceCheck::violation.
  float free_space = 0;
  /// Mean network probability at the pixels of the confirmed samples: the network's belief
  /// where the pose puts the object.
  float map_support = 0;
  /// Of the model points facing the camera, the share matched by a segment point within delta_s
  /// with an agreeing normal (LcpDetail::matched / facing): the segment's shape under the pose.
  float matched = 0;
  /// Of the best bases (up to kConsensusBases), the share that put the object in the same place.
  float consensus = 0;
  /// Of the measured pixels the pose confirms, the share another accepted pose of the frame
  /// confirms and holds at least as strongly (explainPoses); 0 for a pose judged alone.
  float explained = 0;

  static constexpr int kConsensusBases = 8;
  static constexpr int kCount = 6;
  /// Feature names, in the order of features() (CSV columns, calibration output).
  static const std::array<const char*, kCount>& names();
  Eigen::Matrix<double, kCount, 1> features() const;
  static ConfidenceEvidence fromFeatures(const Eigen::Matrix<double, kCount, 1>& f);
  /// The logistic model's inputs, in the same order: the log-odds of the shares that measure the
  /// pose against the data (0.98 of the surface confirmed says much more than 0.90, which a
  /// linear term cannot express), consensus as it is.
  Eigen::Matrix<double, kCount, 1> terms() const;
  /// terms() of the features' best values (weight > 0: 1) or worst (weight <= 0: 0).
  static Eigen::Matrix<double, kCount, 1> limitTerms(bool best);
};

/// The logistic model: confidence = sigmoid(intercept + sum of weight * term), terms from
/// ConfidenceEvidence::terms(). Fitted by scripts/calibrate_confidence.sh (docs/confidence.md); the
/// defaults are the fit for maps that name objects (a network's, masks, labels).
struct ConfidenceModel {
  float intercept = -9.4409f;
  float surface_confirmed = -0.0356f;
  float free_space = -2.1235f;
  float map_support = 1.3279f;
  float matched = 1.0130f;
  float consensus = 1.4922f;
  float explained = -1.4698f;

  /// Key, range and meaning of every coefficient.
  static const ParamSet<ConfidenceModel>& schema();
  /// The weights in the order of ConfidenceEvidence::terms().
  Eigen::Matrix<double, ConfidenceEvidence::kCount, 1> weights() const;
  float confidence(const ConfidenceEvidence& evidence) const;
};

/// The confidence's models and threshold. The inherited coefficients are for maps that name
/// objects; `depth_alone`'s for maps from depth alone (Frame::maps_name_objects false), which mark
/// every region of an object's size alike. Its defaults are the maps' coefficients: a fit of their
/// own served coloured or plain model files but not both (docs/confidence.md).
struct ConfidenceParams : ConfidenceModel {
  ConfidenceModel depth_alone;
  /// Poses below this confidence are rejected: not published, not written to results.
  float min_confidence = 0.25f;

  /// Key, range, unit and meaning of every field (docs/parameters.md).
  static const ParamSet<ConfidenceParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
  /// These settings with `depth_alone`'s coefficients in place of the maps' ones.
  ConfidenceParams forDepthAloneMaps() const;
};

/// Sets the pose's confidence from its evidence, accepts it when it reaches min_confidence, and
/// otherwise says why, naming its weakest evidence.
void judgePose(InstancePose& pose, const ConfidenceParams& params);

}  // namespace stocs
