#include "stocs/sim/synthetic_dataset.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>
#include <utility>

#include "stocs/io/bop_dataset.h"
#include "stocs/io/bop_targets.h"
#include "stocs/io/mesh_io.h"
#include "stocs/sim/bop_writer.h"
#include "stocs/sim/object_catalogue.h"
#include "stocs/sim/segmentation_simulator.h"
#include "stocs/sim/synthetic_frame.h"
#include "stocs/util/error.h"
#include "stocs/util/random.h"

namespace stocs {
namespace fs = std::filesystem;

namespace {

/// Distinct colours (BGR) for object ids 1..8; later ids reuse them.
cv::Vec3b objectColour(int obj_id) {
  static const cv::Vec3b palette[] = {{40, 50, 200},  {190, 110, 40}, {60, 170, 60},
                                      {40, 190, 220}, {170, 60, 150}, {30, 120, 230},
                                      {160, 160, 60}, {120, 60, 60}};
  return palette[(obj_id - 1) % 8];
}

/// Distractors take a random colour, or half of the time one close to a dataset object's, so that
/// the segmentation simulator finds look-alikes.
std::vector<cv::Vec3b> sceneColours(const std::vector<PlacedObject>& objects, Rng& rng) {
  std::vector<cv::Vec3b> colours;
  std::vector<int> ids;
  for (const PlacedObject& o : objects) {
    if (o.obj_id > 0) ids.push_back(o.obj_id);
  }
  for (const PlacedObject& o : objects) {
    if (o.obj_id > 0) {
      colours.push_back(objectColour(o.obj_id));
      continue;
    }
    cv::Vec3b c;
    const bool lookalike = !ids.empty() && uniform01(rng) < 0.5f;
    const cv::Vec3b like =
        lookalike ? objectColour(ids[uniformIndex(rng, static_cast<uint32_t>(ids.size()))]) : c;
    for (int k = 0; k < 3; ++k) {
      const float jitter = 40 * uniform01(rng) - 20;
      c[k] = cv::saturate_cast<uint8_t>(lookalike ? like[k] + jitter : 255 * uniform01(rng));
    }
    colours.push_back(c);
  }
  return colours;
}

void writeImage(const fs::path& file, const cv::Mat& image) {
  fs::create_directories(file.parent_path());
  if (!cv::imwrite(file.string(), image)) {
    throw InputError(fmt::format("{}: cannot write image", file.string()));
  }
}

/// The files of a BOP models folder that a dataset needs (obj_*.ply, models_info.json), checked
/// before anything is written.
std::vector<fs::path> modelFiles(const fs::path& source) {
  std::error_code ec;
  if (!fs::is_directory(source, ec)) {
    throw InputError(fmt::format("synth: models {}: not a folder", source.string()));
  }
  std::vector<fs::path> files;
  bool any_model = false;
  for (const fs::directory_entry& e : fs::directory_iterator(source)) {
    const std::string name = e.path().filename().string();
    const bool model = name.rfind("obj_", 0) == 0 && e.path().extension() == ".ply";
    if (model || name == "models_info.json") files.push_back(e.path());
    any_model |= model;
  }
  if (!any_model) {
    throw InputError(fmt::format("synth: models {}: no obj_*.ply files", source.string()));
  }
  return files;
}

/// The dataset's models: the given files copied, or the catalogue written out when there are none.
void writeModelsFolder(const fs::path& models, const std::vector<fs::path>& files) {
  fs::create_directories(models);
  if (files.empty()) {
    writeModels(models, objectCatalogue());
    return;
  }
  for (const fs::path& file : files) {
    fs::copy_file(file, models / file.filename(), fs::copy_options::overwrite_existing);
  }
}

BopGtInfo visibility(const cv::Mat& labels, int label, long silhouette_pixels) {
  BopGtInfo info;
  const cv::Mat mask = labels == label;
  info.px_count_all = silhouette_pixels;
  info.px_count_visib = cv::countNonZero(mask);
  info.visib_fract =
      silhouette_pixels > 0 ? static_cast<float>(info.px_count_visib) / silhouette_pixels : 0.0f;
  if (info.px_count_visib > 0) {
    const cv::Rect box = cv::boundingRect(mask);
    info.bbox_visib[0] = box.x;
    info.bbox_visib[1] = box.y;
    info.bbox_visib[2] = box.width;
    info.bbox_visib[3] = box.height;
  }
  return info;
}

/// Creates `root` and its test/ folder; throws InputError when `root` holds files or cannot be
/// made.
void createDatasetRoot(const fs::path& root) {
  std::error_code ec;
  if (fs::exists(root, ec) && !fs::is_empty(root, ec)) {
    throw InputError(fmt::format("synth: {} exists and is not empty", root.string()));
  }
  fs::create_directories(root / "test", ec);
  if (ec) {
    throw InputError(fmt::format("synth: cannot create {}: {}", root.string(), ec.message()));
  }
}

/// The dataset's models by id, in metres; throws InputError when its models_info.json lists none.
std::vector<std::pair<int, MeshData>> loadModels(const BopDataset& dataset, const fs::path& root) {
  std::vector<std::pair<int, MeshData>> models;
  for (const auto& [id, info] : dataset.modelsInfo()) {
    models.emplace_back(id, loadMesh(dataset.modelPath(id).string(), 0.001f));
  }
  if (models.empty()) {
    throw InputError(
        fmt::format("synth: {} lists no models", (root / "models" / "models_info.json").string()));
  }
  return models;
}

/// The object id of each placed object (distractors are 0: never a target).
std::vector<int> objectIds(const std::vector<PlacedObject>& objects) {
  std::vector<int> ids;
  for (const PlacedObject& o : objects) ids.push_back(o.obj_id);
  return ids;
}

/// The camera of every image: the intrinsics and the depth scale.
BopFrameCamera bopCamera(const SyntheticDatasetParams& params) {
  BopFrameCamera camera;
  camera.K << params.camera.fx, 0, params.camera.cx, 0, params.camera.fy, params.camera.cy, 0, 0, 1;
  camera.depth_scale = params.depth_scale;
  return camera;
}

/// Writes the scenes of a dataset whose models are in place: each scene's images and JSON files.
class SceneWriter {
 public:
  SceneWriter(const BopDataset& dataset, const SyntheticDatasetParams& params,
              std::vector<std::pair<int, MeshData>> models,
              const std::function<void(const SyntheticImageReport&)>& progress)
      : dataset_(dataset),
        params_(params),
        models_(std::move(models)),
        segmentation_(segmentationPreset(params.segmentation_preset)),
        noise_(params.depth_noise.atLevel(params.depth_noise_level)),
        camera_(bopCamera(params)),
        progress_(progress) {}

  /// Arranges scene `scene` from its own random stream, writes its images and then its
  /// scene_camera, scene_gt and scene_gt_info files; returns the scene's targets.
  std::vector<BopTarget> writeScene(int scene) const {
    Rng rng(streamSeed(params_.seed, static_cast<uint64_t>(scene)));
    const std::vector<PlacedObject> objects = arrangeObjects(models_, params_.layout, rng);
    const std::vector<cv::Vec3b> colours = sceneColours(objects, rng);
    SceneRecords records;
    for (int im = 0; im < params_.images_per_scene; ++im) {
      const auto start = std::chrono::steady_clock::now();
      const Eigen::Isometry3f camera_pose = randomCameraPose(params_.layout, rng);
      writeView(scene, im, objects, colours, camera_pose, records);
      if (progress_) {
        progress_(
            {scene, im, static_cast<int>(records.gt[im].size()),
             std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
      }
    }
    const fs::path dir = dataset_.sceneDir(scene);
    writeSceneCameras(dir / "scene_camera.json", records.cameras);
    writeSceneGroundTruth(dir / "scene_gt.json", records.gt);
    writeSceneGtInfo(dir / "scene_gt_info.json", records.gt_info);
    return records.targets;
  }

 private:
  /// What a scene's JSON files hold, by image id.
  struct SceneRecords {
    std::map<int, BopFrameCamera> cameras;
    std::map<int, std::vector<BopGtInstance>> gt;
    std::map<int, std::vector<BopGtInfo>> gt_info;
    std::vector<BopTarget> targets;
  };

  /// Renders image `im` of a scene from `camera_pose`, writes its images and records its camera
  /// and ground truth.
  void writeView(int scene, int im, const std::vector<PlacedObject>& objects,
                 const std::vector<cv::Vec3b>& colours, const Eigen::Isometry3f& camera_pose,
                 SceneRecords& records) const {
    const uint64_t image_seed =
        streamSeed(params_.seed, (static_cast<uint64_t>(scene + 1) << 32) + im);
    const SyntheticFrame frame =
        renderSyntheticFrame(objects, colours, camera_pose, params_.camera, noise_, image_seed);
    const std::set<int> present =
        writeInstances(dataset_.sceneDir(scene), im, frame, objects, camera_pose, records);
    const SegmentationScene seen{frame.labels, objectIds(objects), frame.rgb};
    const std::vector<BopTarget> targets =
        imageTargets(scene, im, present, records.gt[im], image_seed);
    for (const BopTarget& t : targets) {
      const cv::Mat probability =
          simulateSegmentation(seen, t.obj_id, segmentation_, streamSeed(image_seed, t.obj_id + 2));
      cv::Mat prob16;
      probability.convertTo(prob16, CV_16UC1, 10000.0);
      writeImage(dataset_.probabilityPath(scene, im, t.obj_id), prob16);
    }
    records.targets.insert(records.targets.end(), targets.begin(), targets.end());
    cv::Mat depth16;
    frame.depth.convertTo(depth16, CV_16UC1, 1000.0 / params_.depth_scale);
    writeImage(dataset_.depthPath(scene, im), depth16);
    writeImage(dataset_.rgbPath(scene, im), frame.rgb);
    records.cameras[im] = camera_;
  }

  /// The image's targets by object id: each object present with its instance count, and the
  /// absent ones.
  std::vector<BopTarget> imageTargets(int scene, int im, const std::set<int>& present,
                                      const std::vector<BopGtInstance>& gt,
                                      uint64_t image_seed) const {
    std::vector<BopTarget> targets;
    for (int obj : present) {
      const auto count = std::count_if(gt.begin(), gt.end(),
                                       [obj](const BopGtInstance& g) { return g.obj_id == obj; });
      targets.push_back({scene, im, obj, static_cast<int>(count)});
    }
    for (int obj : absentObjects(present, image_seed)) targets.push_back({scene, im, obj, 0});
    std::sort(targets.begin(), targets.end(),
              [](const BopTarget& a, const BopTarget& b) { return a.obj_id < b.obj_id; });
    return targets;
  }

  /// Up to `absent_per_image` of the dataset's objects that are not in the image, drawn from a
  /// stream of their own (the scene's other draws stay as they were), in increasing id order.
  std::set<int> absentObjects(const std::set<int>& present, uint64_t image_seed) const {
    std::vector<int> spare;
    for (const auto& [id, mesh] : models_) {
      if (!present.count(id)) spare.push_back(id);
    }
    Rng rng(streamSeed(image_seed, 0xab5e47));
    std::set<int> absent;
    while (static_cast<int>(absent.size()) < params_.absent_per_image && !spare.empty()) {
      const size_t k = uniformIndex(rng, static_cast<uint32_t>(spare.size()));
      absent.insert(spare[k]);
      spare.erase(spare.begin() + static_cast<long>(k));
    }
    return absent;
  }

  /// Writes the visible mask of every dataset object in the frame and records its pose and
  /// visibility; returns the object ids present.
  static std::set<int> writeInstances(const fs::path& dir, int im, const SyntheticFrame& frame,
                                      const std::vector<PlacedObject>& objects,
                                      const Eigen::Isometry3f& camera_pose, SceneRecords& records) {
    std::set<int> present;
    std::vector<BopGtInstance>& gt = records.gt[im];
    gt.clear();  // an image whose objects all found no place still gets its (empty) entry
    for (size_t i = 0; i < objects.size(); ++i) {
      if (objects[i].obj_id == 0) continue;
      const Eigen::Isometry3f pose = camera_pose * objects[i].pose;
      gt.push_back({objects[i].obj_id, pose.linear().cast<double>(),
                    pose.translation().cast<double>() * 1000.0});
      const int label = static_cast<int>(i) + 1;
      records.gt_info[im].push_back(visibility(frame.labels, label, frame.silhouette_pixels[i]));
      writeImage(dir / "mask_visib" / fmt::format("{:06d}_{:06d}.png", im, gt.size() - 1),
                 frame.labels == label);
      present.insert(objects[i].obj_id);
    }
    return present;
  }

  const BopDataset& dataset_;
  const SyntheticDatasetParams& params_;
  const std::vector<std::pair<int, MeshData>> models_;
  const SegmentationNoiseParams segmentation_;
  const DepthNoiseParams noise_;
  const BopFrameCamera camera_;
  const std::function<void(const SyntheticImageReport&)>& progress_;
};

}  // namespace

const ParamSet<SyntheticDatasetParams>& SyntheticDatasetParams::schema() {
  using P = SyntheticDatasetParams;
  static const ParamSet<P> schema =
      ParamSet<P>()
          .add(&P::scenes, "scenes", "", ParamRange::closed(1, 100000),
               "scenes (object arrangements)")
          .flag("--scenes")
          .add(&P::images_per_scene, "images_per_scene", "", ParamRange::closed(1, 100000),
               "views of each scene")
          .flag("--images")
          .nest(&P::layout, "layout", SceneLayoutParams::schema())
          .add(&P::depth_noise_level, "depth_noise_level", "", ParamRange::closed(0, 10),
               "depth sensor noise level: 0 exact, 1 a Kinect-like sensor, higher is noisier")
          .flag("--depth-noise")
          .add(&P::segmentation_preset, "segmentation_preset", "", std::nullopt,
               fmt::format("segmentation simulator preset of prob/: {}",
                           fmt::join(segmentationPresetNames(), ", ")))
          .flag("--segmentation")
          .add(&P::absent_per_image, "absent_per_image", "", ParamRange::closed(0, 100),
               "objects per image that are not in the scene but get a probability map (the "
               "simulator's confusion or noise) and a target with inst_count 0 in "
               "test_targets_bop19.json; fewer when the models run out")
          .flag("--absent")
          .add(&P::depth_scale, "depth_scale", "mm", ParamRange::aboveUpTo(0, 100),
               "millimetres per unit of the written depth images")
          .flag("--depth-scale")
          .add(&P::seed, "seed", "", std::nullopt,
               "random seed: the same seed writes the same files")
          .flag("--seed");
  return schema;
}

void SyntheticDatasetParams::validate() const {
  schema().validate(*this, [](const ParamInfo& info) { return "synth: " + info.key; });
  if (!camera.valid()) {
    throw InputError(fmt::format(
        "synth: camera intrinsics are invalid (width {}, height {}, fx {}, fy {}: all must be "
        "positive)",
        camera.width, camera.height, camera.fx, camera.fy));
  }
  layout.checkOrder();
  depth_noise.validate();
  segmentationPreset(segmentation_preset);
}

void writeSyntheticDataset(const fs::path& root, const SyntheticDatasetParams& params,
                           const fs::path& models_dir,
                           const std::function<void(const SyntheticImageReport&)>& progress) {
  params.validate();
  const std::vector<fs::path> model_files =
      models_dir.empty() ? std::vector<fs::path>{} : modelFiles(models_dir);
  createDatasetRoot(root);
  writeModelsFolder(root / "models", model_files);
  const BopDataset dataset(root);
  const SceneWriter writer(dataset, params, loadModels(dataset, root), progress);
  std::vector<BopTarget> targets;
  for (int scene = 0; scene < params.scenes; ++scene) {
    for (const BopTarget& t : writer.writeScene(scene)) targets.push_back(t);
  }
  writeBopTargets(root / "test_targets_bop19.json", targets);
}

}  // namespace stocs
