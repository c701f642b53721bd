#include "stocs/eval/dataset_evaluation.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "stocs/io/bop_targets.h"
#include "stocs/io/mesh_io.h"
#include "stocs/util/error.h"

namespace stocs {

std::vector<Target> listTargets(const BopDataset& dataset, const std::vector<int>& scenes,
                                const std::vector<int>& objects, const ProbabilitySource* source) {
  for (int s : scenes) {
    if (!std::filesystem::is_directory(dataset.sceneDir(s))) {
      throw InputError(
          fmt::format("dataset {}: scene {} does not exist", dataset.root().string(), s));
    }
  }
  const std::set<int> wanted(objects.begin(), objects.end());
  std::map<Target, int> counts;
  for (int scene : scenes.empty() ? dataset.sceneIds() : scenes) {
    for (const auto& [im, instances] : dataset.sceneGroundTruth(scene)) {
      for (const BopGtInstance& g : instances) {
        if ((wanted.empty() || wanted.count(g.obj_id)) &&
            (!source || source->available(scene, im, g.obj_id))) {
          ++counts[{scene, im, g.obj_id}];
        }
      }
    }
  }
  std::vector<Target> targets;
  for (const auto& [target, count] : counts) {
    targets.push_back(target);
    targets.back().inst_count = count;
  }
  return targets;
}

std::vector<Target> targetsFromFile(const BopDataset& dataset, const std::filesystem::path& file,
                                    const std::vector<int>& scenes,
                                    const std::vector<int>& objects) {
  const auto selected = [](const std::vector<int>& list, int id) {
    return list.empty() || std::find(list.begin(), list.end(), id) != list.end();
  };
  std::map<int, std::map<int, std::vector<BopGtInstance>>> gt;  // scene -> image -> instances
  std::vector<Target> targets;
  for (const Target& t : readBopTargets(file)) {
    if (!selected(scenes, t.scene_id) || !selected(objects, t.obj_id)) continue;
    const std::string where = fmt::format("{}: target scene {} image {} object {}", file.string(),
                                          t.scene_id, t.im_id, t.obj_id);
    if (!std::filesystem::is_directory(dataset.sceneDir(t.scene_id))) {
      throw InputError(
          fmt::format("{}: the scene is not in dataset {}", where, dataset.root().string()));
    }
    if (!gt.count(t.scene_id)) gt[t.scene_id] = dataset.sceneGroundTruth(t.scene_id);
    const auto image = gt[t.scene_id].find(t.im_id);
    if (image == gt[t.scene_id].end()) {
      throw InputError(fmt::format("{}: the image has no entry in scene_gt.json", where));
    }
    const bool in_gt = std::any_of(image->second.begin(), image->second.end(),
                                   [&](const BopGtInstance& g) { return g.obj_id == t.obj_id; });
    if (in_gt != (t.inst_count > 0)) {
      throw InputError(fmt::format("{}: inst_count is {} but scene_gt.json {} the object there",
                                   where, t.inst_count, in_gt ? "has" : "does not have"));
    }
    targets.push_back(t);
  }
  std::sort(targets.begin(), targets.end());
  return targets;
}

DatasetEvaluator::DatasetEvaluator(const BopDataset& dataset)
    : dataset_(dataset), info_(dataset.modelsInfo()) {}

const ObjectMetrics& DatasetEvaluator::object(int obj_id) {
  auto it = objects_.find(obj_id);
  if (it != objects_.end()) return it->second;
  const std::filesystem::path file = dataset_.modelPath(obj_id);
  if (!std::filesystem::exists(file)) {
    throw InputError(fmt::format("unknown object {}: {} does not exist", obj_id, file.string()));
  }
  std::vector<Eigen::Vector3f> points = loadMesh(file.string(), 0.001f).vertices;
  for (Eigen::Vector3f& p : points) p *= 1000.0f;  // metrics in the dataset's unit, mm
  const auto info = info_.find(obj_id);
  return objects_
      .emplace(obj_id, ObjectMetrics(std::move(points),
                                     info == info_.end() ? BopObjectInfo{} : info->second))
      .first->second;
}

TargetResult DatasetEvaluator::absentTarget(const Target& target, const BopResult* row) {
  TargetResult result;
  result.target = target;
  result.score = row ? row->score : 0;
  result.errors.found = row != nullptr;  // a pose of an object that is not there: infinite errors
  result.errors.diameter_mm = object(target.obj_id).diameterMm();
  return result;
}

const std::vector<BopGtInstance>& DatasetEvaluator::groundTruth(int scene_id, int im_id) {
  auto scene = gt_.find(scene_id);
  if (scene == gt_.end()) scene = gt_.emplace(scene_id, dataset_.sceneGroundTruth(scene_id)).first;
  const auto image = scene->second.find(im_id);
  if (image == scene->second.end()) {
    throw InputError(fmt::format("scene {} image {} has no ground truth in {}", scene_id, im_id,
                                 (dataset_.sceneDir(scene_id) / "scene_gt.json").string()));
  }
  return image->second;
}

ResultsEvaluation DatasetEvaluator::evaluate(const std::vector<Target>& targets,
                                             const std::vector<BopResult>& results,
                                             const std::string& results_name) {
  ResultsEvaluation out;
  const std::set<Target> target_set(targets.begin(), targets.end());
  std::map<Target, const BopResult*> best;
  for (const BopResult& r : results) {
    const Target key{r.scene_id, r.im_id, r.obj_id};
    try {
      if (!std::filesystem::is_directory(dataset_.sceneDir(r.scene_id))) {
        throw InputError(
            fmt::format("scene {} is not in dataset {}", r.scene_id, dataset_.root().string()));
      }
      groundTruth(r.scene_id, r.im_id);
      object(r.obj_id);
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: row scene {} image {} object {}: {}", results_name,
                                   r.scene_id, r.im_id, r.obj_id, e.what()));
    }
    if (!target_set.count(key)) {
      ++out.not_targets;
      continue;
    }
    const BopResult*& kept = best[key];
    if (kept) ++out.duplicates;
    if (!kept || r.score > kept->score) kept = &r;
  }
  for (const Target& t : targets) {
    std::vector<RigidPose> instances;
    std::vector<int> gt_index;
    const std::vector<BopGtInstance>& gt = groundTruth(t.scene_id, t.im_id);
    for (size_t i = 0; i < gt.size(); ++i) {
      if (gt[i].obj_id != t.obj_id) continue;
      instances.push_back({gt[i].R, gt[i].t_mm});
      gt_index.push_back(static_cast<int>(i));
    }
    TargetResult result;
    result.target = t;
    const auto row = best.find(t);
    if (t.inst_count == 0) {
      out.targets.push_back(absentTarget(t, row == best.end() ? nullptr : row->second));
      continue;
    }
    if (instances.empty()) {
      throw InputError(
          fmt::format("target scene {} image {} object {} has no ground-truth instance", t.scene_id,
                      t.im_id, t.obj_id));
    }
    if (row != best.end()) {
      const RigidPose estimate{row->second->R, row->second->t_mm};
      result.score = row->second->score;
      result.errors = object(t.obj_id).evaluate(&estimate, instances);
      result.gt_index = gt_index[result.errors.instance];
      result.estimate = estimate;
      result.truth = instances[static_cast<size_t>(result.errors.instance)];
    } else {
      result.errors = object(t.obj_id).evaluate(nullptr, instances);
    }
    out.targets.push_back(result);
  }
  return out;
}

}  // namespace stocs
