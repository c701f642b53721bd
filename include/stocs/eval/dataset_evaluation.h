#pragma once
// BOP results against a dataset's ground truth: which (image, object) pairs are targets, and the
// errors of each target's estimate (see object_metrics.h).
//
// A target is one object in one image, however many instances of it the image holds: the
// estimate is compared with the nearest instance. Each target is scored on one estimate, its
// highest-scoring row, so that no instance is claimed twice; further rows for the same target are
// counted and ignored. A target without a row is a missing estimate (infinite errors, a failure).
// An absent target (inst_count 0) has no instance: a row for it is a pose with infinite errors.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "stocs/eval/object_metrics.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/io/bop_results.h"
#include "stocs/io/bop_targets.h"
#include "stocs/sim/probability_source.h"

namespace stocs {

/// A target: one object in one image (see bop_targets.h). Its inst_count is the number of
/// ground-truth instances; 0 for an absent object, asked for by a targets file, whose right answer
/// is no pose.
using Target = BopTarget;

/// Every object of scene_gt.json in every image of the given scenes (empty: all) that is among
/// `objects` (empty: all) and, when `source` is given, has a probability map from it: the pairs
/// `stocs estimate --prob` attempts. Sorted. Throws InputError naming a scene that does not exist.
std::vector<Target> listTargets(const BopDataset& dataset, const std::vector<int>& scenes,
                                const std::vector<int>& objects,
                                const ProbabilitySource* source = nullptr);

/// The targets of a BOP targets file (bop_targets.h) among the given scenes and objects (empty:
/// all), sorted, with their inst_count checked against scene_gt.json: a present target needs a
/// ground-truth instance and an absent one (inst_count 0) must have none. Throws InputError naming
/// the file and the target.
std::vector<Target> targetsFromFile(const BopDataset& dataset,
                                    const std::filesystem::path& targets_file,
                                    const std::vector<int>& scenes,
                                    const std::vector<int>& objects);

struct TargetResult {
  Target target;
  /// The object is not in the image: a pose for it is a false positive.
  bool absent() const { return target.inst_count == 0; }
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

  /// The dataset's models_info.json, by object id.
  const std::map<int, BopObjectInfo>& info() const { return info_; }

 private:
  const std::vector<BopGtInstance>& groundTruth(int scene_id, int im_id);
  /// The result of an absent target with its row (nullptr: none, the right answer).
  TargetResult absentTarget(const Target& target, const BopResult* row);

  const BopDataset& dataset_;
  std::map<int, BopObjectInfo> info_;
  std::map<int, ObjectMetrics> objects_;
  std::map<int, std::map<int, std::vector<BopGtInstance>>> gt_;  ///< scene -> image -> instances
};

}  // namespace stocs
