// `stocs estimate`: one pose per (image, object) of a BOP dataset, written as BOP results.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <chrono>
#include <map>
#include <opencv2/core.hpp>
#include <set>

#include "cli_options.h"
#include "commands.h"
#include "stocs/bop_dataset.h"
#include "stocs/bop_results.h"
#include "stocs/error.h"
#include "stocs/methods/pose_method.h"
#include "stocs/pose_metrics.h"
#include "stocs/probability_source.h"

namespace stocs::tools {
namespace {

struct EstimateOptions {
  std::string dataset;
  std::string out;
  std::string split = "test";
  std::vector<int> scenes;
  std::vector<int> objects;
  std::string boundaries = "auto";
  std::string method = "stocs";
  std::string prob = "real";
  MethodOptions method_options;
  PipelineParams params;
  ModelOptions model;
};

RigidPose toBop(const Eigen::Isometry3f& pose) {
  return {pose.linear().cast<double>(), pose.translation().cast<double>() * 1000.0};
}

/// ADD-S (mm) to the nearest ground-truth instance of the object, or a negative value without one.
double nearestAddS(const PreparedModel& model, const RigidPose& estimate,
                   const std::vector<BopGtInstance>& instances, int obj_id) {
  std::vector<Eigen::Vector3f> points_mm;
  for (const Eigen::Vector3f& p : model.model.points) points_mm.push_back(p * 1000.0f);
  double best = -1;
  for (const BopGtInstance& g : instances) {
    if (g.obj_id != obj_id) continue;
    const double e = addsError(points_mm, estimate, RigidPose{g.R, g.t_mm});
    if (best < 0 || e < best) best = e;
  }
  return best;
}

int runEstimate(const EstimateOptions& o) {
  o.params.validate();
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
  int targets = 0, found = 0;

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

      const auto start = std::chrono::steady_clock::now();
      const CameraIntrinsics k = cam->second.intrinsics(depth.cols, depth.rows);
      const OrganizedCloud cloud = cloudFromDepth(depth, k, cam->second.depth_scale / 1000.0);
      std::map<int, MethodResult> estimates;
      for (int obj : objects) {
        if (probability[obj].size() != depth.size()) {
          throw InputError(fmt::format("{}: probability map is {}x{} but the depth image is {}x{}",
                                       dataset.probabilityPath(scene, im, obj).string(),
                                       probability[obj].cols, probability[obj].rows, depth.cols,
                                       depth.rows));
        }
        MethodInput input;
        input.cloud = &cloud;
        input.focal_px = static_cast<float>(k.fx);
        input.probability = &probability[obj];
        input.boundary = boundary.empty() ? nullptr : &boundary;
        input.model = &models[obj];
        input.params = &o.params;
        estimates[obj] = method->estimate(input);
      }
      const double image_seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

      for (const auto& [obj, e] : estimates) {
        ++targets;
        std::string line = fmt::format("scene {} image {} object {}: segment {} points, ", scene,
                                       im, obj, e.segment_points);
        if (!e.found) {
          fmt::print(stderr, "{}no pose found ({:.3f} s)\n", line, e.seconds);
          continue;
        }
        ++found;
        const RigidPose pose = toBop(e.pose);
        results.push_back({scene, im, obj, e.score, pose.R, pose.t, image_seconds});
        line += fmt::format("score {:.4f}, {} hypotheses, t [{:.1f} {:.1f} {:.1f}] mm, {:.3f} s",
                            e.score, e.hypotheses, pose.t.x(), pose.t.y(), pose.t.z(), e.seconds);
        const double adds = nearestAddS(models[obj], pose, instances, obj);
        const auto it = info.find(obj);
        if (adds >= 0 && it != info.end() && it->second.diameter_mm > 0) {
          line += fmt::format(", ADD-S {:.1f} mm ({:.1f}% of diameter)", adds,
                              100.0 * adds / it->second.diameter_mm);
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
  cmd->add_option("--split", o->split, "Dataset split folder");
  cmd->add_option("--scenes", o->scenes, "Scene ids, comma-separated (default: all)")
      ->delimiter(',');
  cmd->add_option("--objects", o->objects, "Object ids, comma-separated (default: all)")
      ->delimiter(',');
  cmd->add_option("--boundaries", o->boundaries,
                  "Instance boundary maps edge/IMAGE.png: 'auto' uses them where present, 'off' "
                  "ignores them")
      ->check(CLI::IsMember({"auto", "off"}));
  cmd->add_option("--method", o->method,
                  "Pose estimation method: " + fmt::format("{}", fmt::join(methodNames(), ", ")));
  cmd->add_option("--prob", o->prob, "Probability maps: 'real' (the dataset's prob/ maps)");
  cmd->add_option("--hard-threshold", o->method_options.hard_threshold,
                  "Probability threshold of the hard segment for methods that need one");
  addModelOptions(*cmd, o->model);
  addPipelineOptions(*cmd, o->params);
  return {cmd, [o] { return runEstimate(*o); }};
}

}  // namespace stocs::tools
