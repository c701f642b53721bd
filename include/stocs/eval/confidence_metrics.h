#pragma once
// What a method's score is worth (issue 29): how well it ranks correct poses above everything
// else, how well it is calibrated as a probability of being correct, and what a threshold on it
// keeps and rejects. For any method: StoCS's score is its calibrated confidence, a baseline's its
// own score.

#include <vector>

namespace stocs {

/// One target as the confidence metrics see it.
struct ScoredTarget {
  bool posed = false;    ///< the method returned a pose
  double score = 0;      ///< the pose's score (ignored without a pose)
  bool correct = false;  ///< the pose is correct (ADD-S below 10% of the diameter)
  bool absent = false;   ///< the object is not in the image (any pose is wrong)
};

/// Poses whose score falls in [lo, hi) (the last bin includes 1).
struct ReliabilityBin {
  double lo = 0, hi = 0;
  int count = 0;
  double mean_score = 0;     ///< NaN for an empty bin
  double share_correct = 0;  ///< NaN for an empty bin
};

struct ConfidenceMetrics {
  int targets = 0, absent = 0, poses = 0, correct = 0;
  /// ROC AUC of the score between correct poses and every other target (wrong poses, absent
  /// objects; a target without a pose ranks below every score). NaN when either side is empty.
  double roc_auc = 0;
  /// Expected calibration error over the reliability bins: the pose-weighted mean of
  /// |mean score - share correct|. NaN when a score lies outside [0, 1] or there is no pose.
  double ece = 0;
  std::vector<ReliabilityBin> reliability;  ///< equal-width bins over [0, 1]; empty when ece is NaN
  double threshold = 0;
  double precision = 0;         ///< correct poses with score >= t / poses with score >= t
  double recall = 0;            ///< correct poses with score >= t / targets whose object is present
  double absent_posed = 0;      ///< absent targets with a pose of score >= t / absent targets
  double correct_rejected = 0;  ///< correct poses with score < t / correct poses
};

/// Probability that a random positive scores above a random negative, ties counting half
/// (Mann-Whitney U / (n+ n-)). NaN when either list is empty.
double rocAuc(std::vector<double> positives, std::vector<double> negatives);

/// The metrics of `targets` at score threshold `threshold`, calibration over `bins` bins. Ratios
/// with an empty denominator are NaN.
ConfidenceMetrics confidenceMetrics(const std::vector<ScoredTarget>& targets, double threshold,
                                    int bins = 10);

}  // namespace stocs
