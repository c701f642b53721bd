// `stocs estimate`: one pose per (image, object) of a BOP dataset, written as BOP results.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <opencv2/core.hpp>
#include <optional>
#include <set>
#include <vector>

#include "cli_options.h"
#include "commands.h"
#include "report/object_runs.h"
#include "stocs/estimation/frame.h"
#include "stocs/eval/dataset_evaluation.h"
#include "stocs/eval/metric_summary.h"
#include "stocs/eval/pose_metrics.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/io/bop_results.h"
#include "stocs/methods/pose_method.h"
#include "stocs/sim/probability_source.h"
#include "stocs/tracking/frame_tracker.h"
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
  std::string targets;
  bool warm_up = false;
  int repeats = 1;
  double frame_rate = 30;  ///< --track: images per second, by im_id
  MethodOptions method_options;
  PipelineParams params;
  TrackingParams tracking;
  ModelOptions model;
};

RigidPose toBop(const Eigen::Isometry3f& pose) {
  return {pose.linear().cast<double>(), pose.translation().cast<double>() * 1000.0};
}

/// The options' parameters for `method`: the frame-level explanation ranks poses by their
/// confidence, so only a method that gives one is explained.
PipelineParams frameParams(PipelineParams params, const PoseMethod& method) {
  params.explanation.enabled = params.explanation.enabled && method.givesConfidence();
  return params;
}

/// An image of the dataset and the objects the run estimates in it.
struct ImageTargets {
  int scene = 0, im = 0;
  const std::vector<BopGtInstance>* instances = nullptr;  ///< the image's ground truth
  std::set<int> objects;
  BopFrameCamera camera;
};

/// One object's estimate in an image, its times the medians over the repeats.
struct TimedResult {
  int obj = 0;
  PoseEstimate estimate;
  double cpu_seconds = 0;
  std::vector<TrackState> states;  ///< --track: per instance
};

/// `stocs estimate`: every image of the selected scenes in turn, each through the frame loop
/// (estimateFrame) with the chosen method; BOP results and per-object rows at the end.
class EstimateRun {
 public:
  explicit EstimateRun(const EstimateOptions& o)
      : o_(o),
        method_(makeMethod(o.method, o.method_options)),
        params_(frameParams(o.params, *method_)),
        dataset_(o.dataset, o.split),
        probabilities_(makeProbabilitySource(o.prob, dataset_, o.params.stocs.seed)),
        cache_(o.model.cache()),
        warm_up_(o.warm_up) {
    if (o.tracking.enabled) tracker_.emplace(o.tracking);
  }

  int run() {
    int loaded_scene = -1;
    std::map<int, BopFrameCamera> cameras;
    std::map<int, std::vector<BopGtInstance>> gt;
    for (const auto& [image, objects] : selection()) {
      const auto [scene, im] = image;
      if (scene != loaded_scene) {
        if (tracker_) tracker_->reset();  // each scene is a stream of its own
        cameras = dataset_.sceneCameras(scene);
        gt = dataset_.sceneGroundTruth(scene);
        loaded_scene = scene;
      }
      const ImageTargets targets = imageTargets(scene, im, objects, gt[im], cameras);
      report(targets, estimateImage(targets));
    }
    if (targets_ == 0) {
      throw InputError(fmt::format(
          "dataset {}: no (image, object) pair of the selected scenes and objects has a "
          "probability map from source '{}'",
          o_.dataset, o_.prob));
    }
    writeBopResults(o_.out, results_);
    if (!o_.per_object.empty()) writeObjectRuns(o_.per_object, object_runs_);
    fmt::print(stderr, "{} of {} objects found{}; results in {}\n", found_, targets_,
               rejected_ ? fmt::format(", {} poses rejected below min_confidence", rejected_) : "",
               o_.out);
    if (tracker_) {
      fmt::print(stderr,
                 "tracking: {} poses tracked, {} redetected, {} lost, {} hidden; {} full "
                 "detections of {} (image, object) pairs\n",
                 counts_.tracked, counts_.redetected, counts_.lost, counts_.hidden,
                 counts_.detections, targets_);
    }
    return 0;
  }

 private:
  using ImageKey = std::pair<int, int>;  ///< scene, image

  /// The objects to estimate in each image: the targets file's (each must have a map), else every
  /// selected object of scene_gt.json that has a map.
  std::map<ImageKey, std::set<int>> selection() const {
    std::map<ImageKey, std::set<int>> images;
    if (!o_.targets.empty()) {
      for (const Target& t : targetsFromFile(dataset_, o_.targets, o_.scenes, o_.objects)) {
        if (!probabilities_->available(t.scene_id, t.im_id, t.obj_id)) {
          throw InputError(fmt::format(
              "{}: target scene {} image {} object {} has no probability map from source '{}' "
              "({}); --prob sim:PRESET simulates one",
              o_.targets, t.scene_id, t.im_id, t.obj_id, o_.prob,
              dataset_.probabilityPath(t.scene_id, t.im_id, t.obj_id).string()));
        }
        images[{t.scene_id, t.im_id}].insert(t.obj_id);
      }
      return images;
    }
    for (const Target& t : listTargets(dataset_, o_.scenes, o_.objects, probabilities_.get())) {
      images[{t.scene_id, t.im_id}].insert(t.obj_id);
    }
    return images;
  }

  /// The image's objects with its ground truth and camera.
  ImageTargets imageTargets(int scene, int im, const std::set<int>& objects,
                            const std::vector<BopGtInstance>& instances,
                            const std::map<int, BopFrameCamera>& cameras) const {
    const auto cam = cameras.find(im);
    if (cam == cameras.end()) {
      throw InputError(fmt::format("{}: no entry for image {}",
                                   (dataset_.sceneDir(scene) / "scene_camera.json").string(), im));
    }
    return {scene, im, &instances, objects, cam->second};
  }

  /// The object's model, prepared (or loaded from the cache) on its first use.
  const PreparedModel& model(int obj) {
    auto it = models_.find(obj);
    if (it != models_.end()) return it->second;
    CacheReport report;
    PreparedModel& m = models_[obj] = cache_.load(dataset_.modelPath(obj).string(),
                                                  o_.model.unit_scale, o_.params.model, &report);
    if (const auto info = evaluator_.info().find(obj); info != evaluator_.info().end()) {
      m.symmetries = info->second.symmetries();
    }
    fmt::print(stderr, "model {}: {} samples, PPF map {:.2f} MB, {}{}\n", obj, m.model.size(),
               m.ppf_map.memoryBytes() / 1e6, toString(report.outcome),
               report.detail.empty() ? "" : " (" + report.detail + ")");
    method_->prepare(m);
    return m;
  }

  /// The image's raw data (depth, maps, boundary, colour), loaded before any clock starts (BOP's
  /// definition of the time), as a frame without its cloud.
  Frame rawFrame(const ImageTargets& image, cv::Mat& depth) {
    Frame frame;
    frame.maps_name_objects = probabilities_->namesObjects();
    for (int obj : image.objects) {
      model(obj);
      const cv::Mat map = probabilities_->load(image.scene, image.im, obj);
      frame.probabilities[std::to_string(obj)] = map;
    }
    depth = dataset_.loadDepth(image.scene, image.im);
    for (int obj : image.objects) {
      const cv::Mat& map = frame.probabilities[std::to_string(obj)];
      if (map.size() != depth.size()) {
        throw InputError(fmt::format("{}: probability map is {}x{} but the depth image is {}x{}",
                                     dataset_.probabilityPath(image.scene, image.im, obj).string(),
                                     map.cols, map.rows, depth.cols, depth.rows));
      }
    }
    if (o_.boundaries == "auto") frame.boundary = dataset_.loadBoundary(image.scene, image.im);
    frame.colour = dataset_.loadColour(image.scene, image.im, depth.size());
    frame.camera = image.camera.intrinsics(depth.cols, depth.rows);
    return frame;
  }

  /// Every object of the image, o.repeats times (each repeat converts the cloud again): poses of
  /// the first repeat, times the medians; sets image_seconds_ (BOP's time of the image).
  std::vector<TimedResult> estimateImage(const ImageTargets& image) {
    cv::Mat depth;
    Frame frame = rawFrame(image, depth);
    std::vector<FrameObject> objects;
    for (int obj : image.objects) objects.push_back({std::to_string(obj), &models_.at(obj)});
    const ObjectEstimator estimate = [this](const ObjectInput& in) {
      return method_->estimate(in);
    };
    const double metres_per_unit = image.camera.depth_scale / 1000.0;
    if (warm_up_) {
      // The process's first estimate pays once for thread pools and first-touch memory, which a
      // running node pays at start-up: it runs here, untimed and discarded.
      frame.cloud = cloudFromDepth(depth, *frame.camera, metres_per_unit);
      estimateFrame(frame, {objects.front()}, params_, estimate);
      fmt::print(stderr, "warm-up: object {} of scene {} image {} estimated once, untimed\n",
                 objects.front().name, image.scene, image.im);
      warm_up_ = false;
    }
    std::vector<TimedResult> timed(objects.size());
    std::vector<std::vector<double>> wall(objects.size()), cpu(objects.size());
    std::vector<double> image_times;
    for (int repeat = 0; repeat < o_.repeats; ++repeat) {
      const auto start = std::chrono::steady_clock::now();
      frame.cloud = cloudFromDepth(depth, *frame.camera, metres_per_unit);
      std::vector<ObjectResult> results = tracker_
                                              ? trackImage(image, frame, objects, timed)
                                              : estimateFrame(frame, objects, params_, estimate);
      image_times.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      for (size_t k = 0; k < results.size(); ++k) {
        wall[k].push_back(results[k].estimate.seconds);
        cpu[k].push_back(results[k].cpu_seconds);
        if (repeat == 0) {
          timed[k].obj = std::stoi(results[k].name);
          timed[k].estimate = std::move(results[k].estimate);
        }
      }
    }
    for (size_t k = 0; k < timed.size(); ++k) {
      timed[k].estimate.seconds = quantile(wall[k], 0.5);
      timed[k].cpu_seconds = quantile(cpu[k], 0.5);
    }
    image_seconds_ = quantile(image_times, 0.5);
    return timed;
  }

  /// The objects of the image as the next frame of the scene's stream (--track; one repeat): the
  /// tracker's estimates, with the states of their instances put in `timed`.
  std::vector<ObjectResult> trackImage(const ImageTargets& image, const Frame& frame,
                                       const std::vector<FrameObject>& objects,
                                       std::vector<TimedResult>& timed) {
    FrameTracking t = tracker_->track(frame, objects, o_.params, image.im / o_.frame_rate);
    std::vector<ObjectResult> results;
    for (size_t k = 0; k < t.objects.size(); ++k) {
      timed[k].states = std::move(t.objects[k].states);
      results.push_back(std::move(t.objects[k].result));
    }
    counts_.tracked += t.counts.tracked;
    counts_.redetected += t.counts.redetected;
    counts_.lost += t.counts.lost;
    counts_.hidden += t.counts.hidden;
    counts_.detections += t.counts.detections;
    return results;
  }

  /// Writes the image's results and prints a line per object.
  void report(const ImageTargets& image, const std::vector<TimedResult>& timed) {
    for (const TimedResult& t : timed) {
      const PoseEstimate& e = t.estimate;
      ++targets_;
      object_runs_.push_back({{image.scene, image.im, t.obj},
                              e.found(),
                              e.seconds,
                              t.cpu_seconds,
                              e.segment_points,
                              e.hypotheses,
                              e.found() ? e.instances.front().evidence : ConfidenceEvidence{},
                              e.found() ? e.instances.front().confidence : 0.0f});
      if (e.found()) object_runs_.back().covariance = e.instances.front().covariance;
      const std::string head = fmt::format("scene {} image {} object {}: segment {} points, ",
                                           image.scene, image.im, t.obj, e.segment_points);
      if (!e.found()) {
        fmt::print(stderr, "{}no pose found ({:.3f} s)\n", head, e.seconds);
        continue;
      }
      ++found_;
      fmt::print(stderr, "{}{}\n", head, describePoses(image, t, e));
    }
  }

  /// The object's poses as result rows, described by `stocs eval`'s measures (the model file's
  /// vertices) against the nearest ground-truth instance.
  std::string describePoses(const ImageTargets& image, const TimedResult& t,
                            const PoseEstimate& e) {
    const int obj = t.obj;
    const std::vector<BopGtInstance>& instances = *image.instances;
    std::vector<RigidPose> truths;  // the object's instances, and their indices in the image's
    std::vector<int> truth_index;
    for (size_t i = 0; i < instances.size(); ++i) {
      if (instances[i].obj_id != obj) continue;
      truths.push_back({instances[i].R, instances[i].t_mm});
      truth_index.push_back(static_cast<int>(i));
    }
    std::set<int> recalled;  // ground-truth instances within ADD-S 10% of the diameter
    std::string line;
    for (size_t k = 0; k < e.instances.size(); ++k) {
      const InstancePose& instance = e.instances[k];
      const RigidPose pose = toBop(instance.pose);
      if (k > 0) line += fmt::format("\n  instance {}: ", k);
      if (k < t.states.size()) line += fmt::format("{}, ", toString(t.states[k]));
      line += fmt::format("score {:.4f}, t [{:.1f} {:.1f} {:.1f}] mm", instance.score, pose.t.x(),
                          pose.t.y(), pose.t.z());
      // A method with a calibrated confidence writes it as the BOP score, and only accepted poses.
      if (method_->givesConfidence()) {
        line += instance.accepted ? fmt::format(", confidence {:.3f}", instance.confidence)
                                  : ", rejected: " + instance.rejection;
        if (!instance.ambiguous.empty()) line += ", " + ambiguityText(instance.ambiguous);
        rejected_ += !instance.accepted;
      }
      if (!method_->givesConfidence() || instance.accepted) {
        results_.push_back({image.scene, image.im, obj,
                            method_->givesConfidence() ? instance.confidence : instance.score,
                            pose.R, pose.t, image_seconds_});
      }
      if (k == 0) line += fmt::format(", {} hypotheses, {:.3f} s", e.hypotheses, e.seconds);
      if (truths.empty()) continue;
      const TargetErrors errors = evaluator_.object(obj).evaluate(&pose, truths);
      const int near = truth_index[static_cast<size_t>(errors.instance)];
      line += fmt::format(
          ", ADD(-S) {:.1f} mm, ADD-S {:.1f} mm ({:.1f}% of diameter) to instance {}",
          errors.addOrAddsMm(), errors.adds_mm, 100.0 * errors.adds_mm / errors.diameter_mm, near);
      if (errors.addsSuccess()) recalled.insert(near);
    }
    if (e.instances.size() > 1 && !truths.empty()) {
      line += fmt::format("\n  instance recall {} of {} ground-truth instances", recalled.size(),
                          truths.size());
    }
    return line;
  }

  const EstimateOptions& o_;
  const std::unique_ptr<PoseMethod> method_;
  const PipelineParams params_;  // the estimation's, as frameParams gives them
  const BopDataset dataset_;
  const std::unique_ptr<ProbabilitySource> probabilities_;
  const ModelCache cache_;
  /// The log's errors, as `stocs eval` measures them, and the models' declared symmetries.
  DatasetEvaluator evaluator_{dataset_};
  bool warm_up_;
  std::map<int, PreparedModel> models_;
  std::vector<BopResult> results_;
  std::vector<ObjectRun> object_runs_;
  std::optional<FrameTracker> tracker_;  // --track
  TrackingCounts counts_;                // --track: summed over the images
  double image_seconds_ = 0;
  int targets_ = 0, found_ = 0, rejected_ = 0;
};

/// Throws InputError for --track with options it cannot honour.
void checkTrackingOptions(const EstimateOptions& o) {
  validateSchemaOptions(TrackingParams::schema(), o.tracking);
  if (!o.tracking.enabled) return;
  if (o.method != "stocs") {
    throw InputError(fmt::format("--track tracks with StoCS; --method {} cannot track", o.method));
  }
  if (o.repeats != 1) {
    throw InputError(fmt::format(
        "--track processes each image once, as the next frame of its scene; --repeats {} would "
        "track the same image again",
        o.repeats));
  }
}

int runEstimate(EstimateOptions o) {
  validatePipelineOptions(o.params);
  checkTrackingOptions(o);
  // 'off': neither the dataset's boundary maps nor those of the colour image.
  if (o.boundaries == "off") o.params.colour_boundaries.enabled = false;
  return EstimateRun(o).run();
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
                  "seconds, segment points, hypotheses, the first pose's confidence evidence and "
                  "confidence");
  addSelectionOptions(*cmd, o->split, o->scenes, o->objects);
  cmd->add_option("--boundaries", o->boundaries,
                  "Instance boundary maps edge/IMAGE.png: 'auto' uses them where present, else "
                  "boundaries from rgb/ when searching several instances (--colour-boundaries); "
                  "'off' neither")
      ->check(CLI::IsMember({"auto", "off"}));
  cmd->add_option("--method", o->method,
                  "Pose estimation method: " + fmt::format("{}", fmt::join(methodNames(), ", ")));
  cmd->add_option("--prob", o->prob, "Probability maps: " + probabilitySourceHelp());
  cmd->add_option("--targets", o->targets,
                  "BOP targets file (test_targets_bop19.json: scene_id, im_id, obj_id, "
                  "inst_count): estimate exactly these (image, object) pairs, inst_count 0 "
                  "(absent objects) included; default: every object of scene_gt.json with a map");
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
  cmd->add_option("--frame-rate", o->frame_rate,
                  "With --track: images per second; image im_id is the frame at im_id / rate s")
      ->check(CLI::PositiveNumber);
  static const ParamSet<EstimateOptions> tracking = ParamSet<EstimateOptions>().nest(
      &EstimateOptions::tracking, "tracking", TrackingParams::schema(), "Tracking (--track)");
  addSchemaOptions(*cmd, tracking, *o);
  addModelOptions(*cmd, o->model);
  addPipelineOptions(*cmd, o->params);
  return {cmd, [o] { return runEstimate(*o); }};
}

}  // namespace stocs::tools
