#pragma once
// BOP results against a dataset's ground truth: which (image, object) pairs are targets, and the
// errors of each target's estimate (see object_metrics.h).
//
// A target is one object in one image, however many instances of it the image holds: the
// estimate is compared with the nearest instance. Each target is scored on one estimate, its
// highest-scoring row, so that no instance is claimed twice; further rows for the same target are
// counted and ignored. A target without a row is a missing estimate (infinite errors, a failure).

#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "stocs/eval/object_metrics.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/io/bop_results.h"
#include "stocs/sim/probability_source.h"

namespace stocs {

struct Target {
  int scene_id = 0;
  int im_id = 0;
  int obj_id = 0;

  bool operator<(const Target& o) const {
    return std::tie(scene_id, im_id, obj_id) < std::tie(o.scene_id, o.im_id, o.obj_id);
  }
  bool operator==(const Target& o) const { return !(*this < o) && !(o < *this); }
};

/// Every object of scene_gt.json in every image of the given scenes (empty: all) that is among
/// `objects` (empty: all) and, when `source` is given, has a probability map from it: the pairs
/// `stocs estimate --prob` attempts. Sorted. Throws InputError naming a scene that does not exist.
std::vector<Target> listTargets(const BopDataset& dataset, const std::vector<int>& scenes,
                                const std::vector<int>& objects,
                                const ProbabilitySource* source = nullptr);

struct TargetResult {
  Target target;
  double score = 0;   ///< of the evaluated row
  int gt_index = -1;  ///< matched entry of scene_gt.json for the image; -1 when missing
  TargetErrors errors;
  RigidPose estimate;  ///< the evaluated row's pose (mm); identity when missing
  RigidPose truth;     ///< the matched ground-truth instance (mm); identity when missing
};

struct ResultsEvaluation {
  std::vector<TargetResult> targets;  ///< in the order of the target list
  int duplicates = 0;   ///< rows for a target beyond its highest-scoring one (ignored)
  int not_targets = 0;  ///< rows for an object that is not a target of its image (ignored)
};

class DatasetEvaluator {
 public:
  explicit DatasetEvaluator(const BopDataset& dataset);

  /// Scores `results` on `targets`. Throws InputError, naming `results_name` and the row, for a
  /// scene that is not in the dataset, an image without ground truth, or an unknown object (no
  /// model file).
  ResultsEvaluation evaluate(const std::vector<Target>& targets,
                             const std::vector<BopResult>& results,
                             const std::string& results_name);

  /// The metrics of an object, its model (every vertex, mm) loaded on first use. Throws InputError
  /// for an object without a model file.
  const ObjectMetrics& object(int obj_id);

 private:
  const std::vector<BopGtInstance>& groundTruth(int scene_id, int im_id);

  const BopDataset& dataset_;
  std::map<int, BopObjectInfo> info_;
  std::map<int, ObjectMetrics> objects_;
  std::map<int, std::map<int, std::vector<BopGtInstance>>> gt_;  ///< scene -> image -> instances
};

}  // namespace stocs
