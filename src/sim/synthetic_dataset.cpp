#include "stocs/sim/synthetic_dataset.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <set>
#include <utility>

#include "scene_writer.h"
#include "stocs/io/mesh_io.h"
#include "stocs/sim/lookalikes.h"
#include "stocs/sim/object_catalogue.h"
#include "stocs/util/error.h"
#include "stocs/util/random.h"
#include "synthetic_sequence.h"

namespace stocs {
namespace fs = std::filesystem;

namespace {

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
    if (model || name == "models_info.json" || name == "lookalikes.json") {
      files.push_back(e.path());
    }
    any_model |= model;
  }
  if (!any_model) {
    throw InputError(fmt::format("synth: models {}: no obj_*.ply files", source.string()));
  }
  return files;
}

/// Throws InputError naming the first model file of `files` without faces: scenes are rendered
/// from triangles, and a point model would leave its images without it and its masks empty.
void checkModelsAreMeshes(const std::vector<fs::path>& files) {
  for (const fs::path& file : files) {
    if (file.extension() != ".ply") continue;
    if (!loadMesh(file.string(), 0.001f).isMesh()) {
      throw InputError(fmt::format(
          "synth: model {} has no faces (a point model): scenes are rendered from triangles, so "
          "it would be in no image and no mask; give its mesh",
          file.string()));
    }
  }
}

/// The dataset's models: the given files copied, or the catalogue objects written out when there
/// are none.
void writeModelsFolder(const fs::path& models, const std::vector<fs::path>& files,
                       const std::vector<CatalogueObject>& catalogue) {
  fs::create_directories(models);
  if (files.empty()) {
    writeModels(models, catalogue);
    const Lookalikes pairs = catalogueLookalikes(catalogue);
    if (!pairs.empty()) writeLookalikes(models / "lookalikes.json", pairs);
    return;
  }
  for (const fs::path& file : files) {
    fs::copy_file(file, models / file.filename(), fs::copy_options::overwrite_existing);
  }
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

/// The dataset's models by id, in metres, as read back from their files; a catalogue object's
/// vertex colours are the catalogue's, whatever the files keep of them. Throws InputError when
/// models_info.json lists none.
std::vector<std::pair<int, MeshData>> loadModels(const BopDataset& dataset, const fs::path& root,
                                                 const std::vector<CatalogueObject>& catalogue) {
  std::vector<std::pair<int, MeshData>> models;
  for (const auto& [id, info] : dataset.modelsInfo()) {
    models.emplace_back(id, loadMesh(dataset.modelPath(id).string(), 0.001f));
  }
  for (const CatalogueObject& o : catalogue) {
    for (auto& [id, mesh] : models) {
      if (id == o.id && o.mesh.hasColour()) mesh.colours = o.mesh.colours;
    }
  }
  if (models.empty()) {
    throw InputError(
        fmt::format("synth: {} lists no models", (root / "models" / "models_info.json").string()));
  }
  return models;
}

/// The handle of each catalogue object that has one, by id.
std::map<int, MeshData> handlesOf(const std::vector<CatalogueObject>& catalogue) {
  std::map<int, MeshData> handles;
  for (const CatalogueObject& o : catalogue) {
    if (!o.handle.vertices.empty()) handles[o.id] = o.handle;
  }
  return handles;
}

/// `models` without one member, drawn from `seed`, of each look-alike pair, so that a scene holds
/// at most one of the pair and the other is left to be an absent target that fits; `models` as
/// they are when there are no pairs.
std::vector<std::pair<int, MeshData>> oneOfEachPair(
    const std::vector<std::pair<int, MeshData>>& models, const Lookalikes& lookalikes,
    uint64_t seed) {
  if (lookalikes.empty()) return models;
  Rng rng(seed);
  std::set<int> left_out;
  for (const auto& [id, others] : lookalikes) {
    for (int other : others) {
      if (id > other || left_out.count(id) || left_out.count(other)) continue;
      left_out.insert(uniform01(rng) < 0.5f ? id : other);
    }
  }
  std::vector<std::pair<int, MeshData>> kept;
  for (const auto& model : models) {
    if (!left_out.count(model.first)) kept.push_back(model);
  }
  return kept;
}

/// The objects of a scene: a packed bin with `params.bin.object`, else a tabletop arrangement of
/// at most one object of each look-alike pair.
std::vector<PlacedObject> arrangeScene(const SceneWriter& writer, int scene, Rng& rng) {
  const SyntheticDatasetParams& params = writer.params();
  const std::vector<std::pair<int, MeshData>>& models = writer.models();
  if (params.bin.object == 0) {
    constexpr uint64_t kPairs = 0x9a125;  // the stream that leaves out look-alike partners
    const uint64_t seed = streamSeed(streamSeed(params.seed, static_cast<uint64_t>(scene)), kPairs);
    return arrangeObjects(oneOfEachPair(models, writer.lookalikes(), seed), params.layout, rng);
  }
  for (const auto& [id, mesh] : models) {
    if (id == params.bin.object) return arrangePackedBin(id, mesh, params.bin, rng);
  }
  throw InputError(
      fmt::format("synth: --packed-bin {}: the dataset has no such object", params.bin.object));
}

/// Throws InputError, before anything is written, when `--packed-bin` names an object that neither
/// the catalogue nor the models folder holds.
void checkBinObject(int object, const std::vector<CatalogueObject>& catalogue,
                    const std::vector<fs::path>& model_files) {
  if (object == 0) return;
  std::vector<int> ids;
  for (const CatalogueObject& o : catalogue) ids.push_back(o.id);
  for (const fs::path& file : model_files) {
    int id = 0;
    if (std::sscanf(file.filename().string().c_str(), "obj_%d.ply", &id) == 1) ids.push_back(id);
  }
  if (std::find(ids.begin(), ids.end(), object) == ids.end()) {
    throw InputError(fmt::format("synth: --packed-bin {}: no such object among the models ({})",
                                 object, fmt::join(ids, ", ")));
  }
}

/// Scene `scene`: an arrangement from its own random stream viewed from `images_per_scene` random
/// cameras; returns its targets.
std::vector<BopTarget> writeRandomViews(const SceneWriter& writer, int scene) {
  const SyntheticDatasetParams& params = writer.params();
  Rng rng(streamSeed(params.seed, static_cast<uint64_t>(scene)));
  const std::vector<PlacedObject> objects = arrangeScene(writer, scene, rng);
  const std::vector<cv::Vec3b> colours = sceneColours(objects, params.look, rng);
  SceneRecords records;
  for (int im = 0; im < params.images_per_scene; ++im) {
    const auto start = std::chrono::steady_clock::now();
    SceneView view;
    view.scene = scene;
    view.im = im;
    view.objects = &objects;
    view.colours = &colours;
    view.camera_pose = randomCameraPose(params.layout, rng);
    view.image_seed = streamSeed(params.seed, (static_cast<uint64_t>(scene + 1) << 32) + im);
    view.absent_seed = view.image_seed;
    view.look_seed = view.image_seed;
    view.segmentation_seeds = [seed = view.image_seed](int obj_id) {
      const uint64_t s = streamSeed(seed, obj_id + 2);
      return SegmentationSeeds{s, s, 0};
    };
    writer.writeView(view, records, start);
  }
  writer.writeSceneFiles(scene, records);
  return records.targets;
}

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
          .flag("--seed")
          .nest(&P::sequence, "sequence", SequenceParams::schema(), "Sequences")
          .nest(&P::look, "look", SceneLookParams::schema(), "Look")
          .add(&P::catalogue, "catalogue", "", std::nullopt,
               fmt::format("generated objects when no --models folder is given: {} (standard: "
                           "ids 1-6; textured: the vertex-coloured ids 7-9, a labelled box, a "
                           "printed can and a printed mug; all: both; lookalike: ids 1-6 and "
                           "their look-alikes, 10 a small box like box 1 and 11 a can like the "
                           "mug's body, pairs in models/lookalikes.json)",
                           fmt::join(catalogueSelectionNames(), ", ")))
          .flag("--catalogue")
          .nest(&P::bin, "bin", PackedBinParams::schema(), "Packed bin");
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
  sequence.validate();
  if (sequence.enabled && images_per_scene != 1) {
    throw InputError(fmt::format(
        "synth: --images {} does not apply to a sequence, whose images are its frames: set their "
        "number with --frames",
        images_per_scene));
  }
  if (sequence.enabled && bin.object != 0) {
    throw InputError(fmt::format(
        "synth: --packed-bin {} makes random views of a bin; it does not apply to a sequence",
        bin.object));
  }
  depth_noise.validate();
  segmentationPreset(segmentation_preset);
  catalogueSelection(catalogue);
}

void writeSyntheticDataset(const fs::path& root, const SyntheticDatasetParams& params,
                           const fs::path& models_dir,
                           const std::function<void(const SyntheticImageReport&)>& progress) {
  params.validate();
  if (!models_dir.empty() && params.catalogue != SyntheticDatasetParams().catalogue) {
    throw InputError(fmt::format(
        "synth: --catalogue {} selects generated objects: it does not apply with --models",
        params.catalogue));
  }
  const std::vector<fs::path> model_files =
      models_dir.empty() ? std::vector<fs::path>{} : modelFiles(models_dir);
  const std::vector<CatalogueObject> catalogue =
      models_dir.empty() ? catalogueSelection(params.catalogue) : std::vector<CatalogueObject>{};
  checkModelsAreMeshes(model_files);
  checkBinObject(params.bin.object, catalogue, model_files);
  if (!models_dir.empty()) readLookalikes(models_dir / "lookalikes.json");  // malformed: say so now
  createDatasetRoot(root);
  writeModelsFolder(root / "models", model_files, catalogue);
  const BopDataset dataset(root);
  const SceneWriter writer(dataset, params, loadModels(dataset, root, catalogue),
                           handlesOf(catalogue), readLookalikes(lookalikesPath(root)), progress);
  std::vector<BopTarget> targets;
  for (int scene = 0; scene < params.scenes; ++scene) {
    const std::vector<BopTarget> scene_targets = params.sequence.enabled
                                                     ? writeSequenceScene(writer, scene)
                                                     : writeRandomViews(writer, scene);
    targets.insert(targets.end(), scene_targets.begin(), scene_targets.end());
  }
  writeBopTargets(root / "test_targets_bop19.json", targets);
}

}  // namespace stocs
