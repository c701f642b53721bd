// `stocs estimate`: one pose per (image, object) of a BOP dataset, written as BOP results.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <opencv2/core.hpp>
#include <set>
#include <vector>

#include "cli_options.h"
#include "commands.h"
#include "object_runs.h"
#include "stocs/eval/metric_summary.h"
#include "stocs/eval/pose_metrics.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/io/bop_results.h"
#include "stocs/methods/pose_method.h"
#include "stocs/sim/probability_source.h"
#include "stocs/util/error.h"

namespace stocs::tools {
namespace {

struct EstimateOptions {
  std::string dataset;
  std::string out;
  std::string per_object;
  std::string split = "test";
  std::vector<int> scenes;
  std::vector<int> objects;
  std::string boundaries = "auto";
  std::string method = "stocs";
  std::string prob = "real";
  bool warm_up = false;
  int repeats = 1;
  MethodOptions method_options;
  PipelineParams params;
  ModelOptions model;
};

RigidPose toBop(const Eigen::Isometry3f& pose) {
  return {pose.linear().cast<double>(), pose.translation().cast<double>() * 1000.0};
}

/// The ground-truth instance of the object nearest to a pose by ADD-S.
struct NearestInstance {
  int index = -1;    ///< into the image's instances; -1 when the object has none
  double adds = -1;  ///< mm
};

NearestInstance nearestInstance(const std::vector<Eigen::Vector3f>& points_mm,
                                const RigidPose& estimate,
                                const std::vector<BopGtInstance>& instances, int obj_id) {
  NearestInstance best;
  for (size_t i = 0; i < instances.size(); ++i) {
    if (instances[i].obj_id != obj_id) continue;
    const double e = addsError(points_mm, estimate, RigidPose{instances[i].R, instances[i].t_mm});
    if (best.index < 0 || e < best.adds) best = {static_cast<int>(i), e};
  }
  return best;
}

int runEstimate(const EstimateOptions& o) {
  validatePipelineOptions(o.params);
  const std::unique_ptr<PoseMethod> method = makeMethod(o.method, o.method_options);
  const BopDataset dataset(o.dataset, o.split);
  const std::unique_ptr<ProbabilitySource> probabilities =
      makeProbabilitySource(o.prob, dataset, o.params.stocs.seed);
  const std::map<int, BopObjectInfo> info = dataset.modelsInfo();
  const ModelCache cache = o.model.cache();
  std::vector<int> scenes = o.scenes.empty() ? dataset.sceneIds() : o.scenes;
  for (int s : scenes) {
    if (!std::filesystem::is_directory(dataset.sceneDir(s))) {
      throw InputError(fmt::format("dataset {}: scene {} does not exist", o.dataset, s));
    }
  }
  const std::set<int> wanted(o.objects.begin(), o.objects.end());
  std::map<int, PreparedModel> models;
  std::vector<BopResult> results;
  std::vector<ObjectRun> object_runs;
  int targets = 0, found = 0;
  bool warm_up = o.warm_up;

  for (int scene : scenes) {
    const std::map<int, BopFrameCamera> cameras = dataset.sceneCameras(scene);
    for (const auto& [im, instances] : dataset.sceneGroundTruth(scene)) {
      std::set<int> objects;
      for (const BopGtInstance& g : instances) {
        if ((wanted.empty() || wanted.count(g.obj_id)) &&
            probabilities->available(scene, im, g.obj_id)) {
          objects.insert(g.obj_id);
        }
      }
      if (objects.empty()) continue;
      const auto cam = cameras.find(im);
      if (cam == cameras.end()) {
        throw InputError(fmt::format("{}: no entry for image {}",
                                     (dataset.sceneDir(scene) / "scene_camera.json").string(), im));
      }
      // Raw data first: models and images are loaded before the clock starts (BOP's definition).
      std::map<int, cv::Mat> probability;
      for (int obj : objects) {
        if (!models.count(obj)) {
          CacheReport report;
          models[obj] = cache.load(dataset.modelPath(obj).string(), o.model.unit_scale,
                                   o.params.model, &report);
          fmt::print(stderr, "model {}: {} samples, PPF map {:.2f} MB, {}{}\n", obj,
                     models[obj].model.size(), models[obj].ppf_map.memoryBytes() / 1e6,
                     toString(report.outcome),
                     report.detail.empty() ? "" : " (" + report.detail + ")");
          method->prepare(models[obj]);
        }
        probability[obj] = probabilities->load(scene, im, obj);
      }
      const cv::Mat depth = dataset.loadDepth(scene, im);
      const cv::Mat boundary = o.boundaries == "auto" ? dataset.loadBoundary(scene, im) : cv::Mat();

      for (int obj : objects) {
        if (probability[obj].size() != depth.size()) {
          throw InputError(fmt::format("{}: probability map is {}x{} but the depth image is {}x{}",
                                       dataset.probabilityPath(scene, im, obj).string(),
                                       probability[obj].cols, probability[obj].rows, depth.cols,
                                       depth.rows));
        }
      }
      const CameraIntrinsics k = cam->second.intrinsics(depth.cols, depth.rows);
      auto inputFor = [&](int obj, const OrganizedCloud& cloud) {
        MethodInput input;
        input.cloud = &cloud;
        input.focal_px = static_cast<float>(k.fx);
        input.camera = &k;
        input.probability = &probability[obj];
        input.boundary = boundary.empty() ? nullptr : &boundary;
        input.model = &models[obj];
        input.params = &o.params;
        return input;
      };
      if (warm_up) {
        // The process's first estimate pays once for thread pools and first-touch memory, which a
        // running node pays at start-up: it runs here, untimed and discarded.
        const OrganizedCloud cloud = cloudFromDepth(depth, k, cam->second.depth_scale / 1000.0);
        method->estimate(inputFor(*objects.begin(), cloud));
        fmt::print(stderr, "warm-up: object {} of scene {} image {} estimated once, untimed\n",
                   *objects.begin(), scene, im);
        warm_up = false;
      }

      // Each repeat converts the cloud and estimates every object again; the poses are those of
      // the first repeat and the times the medians over the repeats.
      std::map<int, MethodResult> estimates;
      std::map<int, std::vector<double>> wall_seconds, cpu_seconds;
      std::vector<double> image_times;
      for (int repeat = 0; repeat < o.repeats; ++repeat) {
        const auto start = std::chrono::steady_clock::now();
        const OrganizedCloud cloud = cloudFromDepth(depth, k, cam->second.depth_scale / 1000.0);
        for (int obj : objects) {  // objects run one after the other: all threads count
          const double cpu_start = processCpuSeconds();
          MethodResult e = method->estimate(inputFor(obj, cloud));
          cpu_seconds[obj].push_back(processCpuSeconds() - cpu_start);
          wall_seconds[obj].push_back(e.seconds);
          if (repeat == 0) estimates[obj] = std::move(e);
        }
        image_times.push_back(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      }
      const double image_seconds = quantile(image_times, 0.5);
      for (auto& [obj, e] : estimates) e.seconds = quantile(wall_seconds[obj], 0.5);

      for (const auto& [obj, e] : estimates) {
        ++targets;
        object_runs.push_back({{scene, im, obj},
                               e.found,
                               e.seconds,
                               quantile(cpu_seconds[obj], 0.5),
                               e.segment_points,
                               e.hypotheses});
        std::string line = fmt::format("scene {} image {} object {}: segment {} points, ", scene,
                                       im, obj, e.segment_points);
        if (!e.found) {
          fmt::print(stderr, "{}no pose found ({:.3f} s)\n", line, e.seconds);
          continue;
        }
        ++found;
        const std::vector<ScoredPose> poses =
            e.instances.empty() ? std::vector<ScoredPose>{{e.pose, e.score}} : e.instances;
        const auto it = info.find(obj);
        const double diameter = it != info.end() ? it->second.diameter_mm : 0;
        std::vector<Eigen::Vector3f> points_mm;  // once for all poses of the target
        for (const Eigen::Vector3f& p : models[obj].model.points) points_mm.push_back(p * 1000.0f);
        std::set<int> recalled;  // ground-truth instances within ADD-S 10% of the diameter
        for (size_t k = 0; k < poses.size(); ++k) {
          const RigidPose pose = toBop(poses[k].pose);
          results.push_back({scene, im, obj, poses[k].score, pose.R, pose.t, image_seconds});
          if (k > 0) line += fmt::format("\n  instance {}: ", k);
          line += fmt::format("score {:.4f}, t [{:.1f} {:.1f} {:.1f}] mm", poses[k].score,
                              pose.t.x(), pose.t.y(), pose.t.z());
          if (k == 0) line += fmt::format(", {} hypotheses, {:.3f} s", e.hypotheses, e.seconds);
          const NearestInstance near = nearestInstance(points_mm, pose, instances, obj);
          if (near.index < 0 || diameter <= 0) continue;
          line += fmt::format(", ADD-S {:.1f} mm ({:.1f}% of diameter) to instance {}", near.adds,
                              100.0 * near.adds / diameter, near.index);
          if (near.adds < 0.1 * diameter) recalled.insert(near.index);
        }
        const auto truths = std::count_if(instances.begin(), instances.end(),
                                          [&](const BopGtInstance& g) { return g.obj_id == obj; });
        if (poses.size() > 1 && truths > 0) {
          line += fmt::format("\n  instance recall {} of {} ground-truth instances",
                              recalled.size(), truths);
        }
        fmt::print(stderr, "{}\n", line);
      }
    }
  }
  if (targets == 0) {
    throw InputError(fmt::format(
        "dataset {}: no (image, object) pair of the selected scenes and objects has a probability "
        "map from source '{}'",
        o.dataset, o.prob));
  }
  writeBopResults(o.out, results);
  if (!o.per_object.empty()) writeObjectRuns(o.per_object, object_runs);
  fmt::print(stderr, "{} of {} objects found; results in {}\n", found, targets, o.out);
  return 0;
}

}  // namespace

Command registerEstimate(CLI::App& app) {
  auto o = std::make_shared<EstimateOptions>();
  CLI::App* cmd =
      app.add_subcommand("estimate", "Estimate object poses on a BOP dataset, write BOP results");
  cmd->add_option("--dataset", o->dataset, "BOP dataset folder (models/, test/)")->required();
  cmd->add_option("--out", o->out, "Results file (BOP CSV)")->required();
  cmd->add_option("--per-object", o->per_object,
                  "Also write a CSV row per attempted object: found, the method's wall and CPU "
                  "seconds, segment points, hypotheses");
  addSelectionOptions(*cmd, o->split, o->scenes, o->objects);
  cmd->add_option("--boundaries", o->boundaries,
                  "Instance boundary maps edge/IMAGE.png: 'auto' uses them where present, 'off' "
                  "ignores them")
      ->check(CLI::IsMember({"auto", "off"}));
  cmd->add_option("--method", o->method,
                  "Pose estimation method: " + fmt::format("{}", fmt::join(methodNames(), ", ")));
  cmd->add_option("--prob", o->prob, "Probability maps: " + probabilitySourceHelp());
  cmd->add_option("--hard-threshold", o->method_options.hard_threshold,
                  "Probability threshold of the hard segment for methods that need one");
  cmd->add_flag("--warm-up", o->warm_up,
                "Estimate the first object once, untimed, before the timed run: per-object times "
                "then leave out the process's first-call costs, as in a running node");
  cmd->add_option(
         "--repeats", o->repeats,
         "Process every image this many times in a row: times are the medians over the "
         "repeats (single runs of a few milliseconds vary by a third on a shared machine), "
         "poses those of the first")
      ->check(CLI::Range(1, 1000));
  addModelOptions(*cmd, o->model);
  addPipelineOptions(*cmd, o->params);
  return {cmd, [o] { return runEstimate(*o); }};
}

}  // namespace stocs::tools
