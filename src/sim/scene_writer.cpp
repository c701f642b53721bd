#include "scene_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "stocs/sim/depth_renderer.h"
#include "stocs/sim/object_catalogue.h"
#include "stocs/sim/synthetic_frame.h"
#include "stocs/util/error.h"
#include "stocs/util/random.h"

namespace stocs {
namespace fs = std::filesystem;

namespace {

/// The plain colour (BGR) of object `obj_id` (object_catalogue.h).
cv::Vec3b objectColour(int obj_id) {
  const Rgba rgb = plainColour(obj_id);
  return {rgb[2], rgb[1], rgb[0]};
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

/// Writes the visible mask of every dataset object in the frame and records its pose and
/// visibility; returns the object ids present.
std::set<int> writeInstances(const fs::path& dir, int im, const SyntheticFrame& frame,
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

/// How much of the handle of each instance that has one the frame shows: the handle's pixels drawn
/// alone, and those where the visible surface is the same object within 0.5 mm of its depth.
std::vector<HandleVisibility> handleVisibility(const SyntheticFrame& frame,
                                               const std::vector<PlacedObject>& objects,
                                               const Eigen::Isometry3f& camera_pose,
                                               const std::map<int, MeshData>& handles,
                                               const CameraIntrinsics& camera) {
  constexpr double kSameSurface = 0.0005;  // metres
  std::vector<HandleVisibility> seen;
  int gt_index = 0;
  for (size_t i = 0; i < objects.size(); ++i) {
    if (objects[i].obj_id == 0) continue;
    const auto handle = handles.find(objects[i].obj_id);
    if (handle != handles.end()) {
      DepthRenderer alone(camera);
      alone.draw(handle->second, camera_pose * objects[i].pose, 1);
      const cv::Mat drawn = alone.depth() > 0;
      const cv::Mat same = cv::abs(alone.depth() - frame.exact_depth) < kSameSurface;
      const cv::Mat visible = drawn & same & (frame.labels == static_cast<int>(i) + 1);
      seen.push_back(
          {gt_index, objects[i].obj_id, cv::countNonZero(drawn), cv::countNonZero(visible)});
    }
    ++gt_index;
  }
  return seen;
}

}  // namespace

void writeImage(const fs::path& file, const cv::Mat& image) {
  fs::create_directories(file.parent_path());
  if (!cv::imwrite(file.string(), image)) {
    throw InputError(fmt::format("{}: cannot write image", file.string()));
  }
}

namespace {

/// Each dataset object its palette colour; each distractor, for a share `lookalike_share`, one
/// within `jitter` levels of a dataset object's, else a random one.
std::vector<cv::Vec3b> drawColours(const std::vector<PlacedObject>& objects, float lookalike_share,
                                   float jitter, Rng& rng) {
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
    const bool lookalike = !ids.empty() && uniform01(rng) < lookalike_share;
    const cv::Vec3b like =
        lookalike ? objectColour(ids[uniformIndex(rng, static_cast<uint32_t>(ids.size()))]) : c;
    for (int k = 0; k < 3; ++k) {
      const float offset = 2 * jitter * uniform01(rng) - jitter;
      c[k] = cv::saturate_cast<uint8_t>(lookalike ? like[k] + offset : 255 * uniform01(rng));
    }
    colours.push_back(c);
  }
  return colours;
}

}  // namespace

std::vector<cv::Vec3b> sceneColours(const std::vector<PlacedObject>& objects,
                                    const SceneLookParams& look, Rng& rng) {
  // `rng` advances as with the default options whatever they are, so that the views drawn after
  // the colours, and with them the ground truth, do not depend on the look-alike options.
  Rng own = rng;
  const SceneLookParams standard;
  const std::vector<cv::Vec3b> colours =
      drawColours(objects, standard.lookalike_share, standard.lookalike_jitter, rng);
  if (look.lookalike_share == standard.lookalike_share &&
      look.lookalike_jitter == standard.lookalike_jitter) {
    return colours;
  }
  return drawColours(objects, look.lookalike_share, look.lookalike_jitter, own);
}

SceneWriter::SceneWriter(const BopDataset& dataset, const SyntheticDatasetParams& params,
                         std::vector<std::pair<int, MeshData>> models,
                         std::map<int, MeshData> handles, Lookalikes lookalikes,
                         const std::function<void(const SyntheticImageReport&)>& progress)
    : dataset_(dataset),
      params_(params),
      models_(std::move(models)),
      handles_(std::move(handles)),
      lookalikes_(std::move(lookalikes)),
      segmentation_(segmentationPreset(params.segmentation_preset)),
      noise_(params.depth_noise.atLevel(params.depth_noise_level)),
      camera_(bopCamera(params)),
      progress_(progress) {}

void SceneWriter::writeView(const SceneView& view, SceneRecords& records,
                            std::chrono::steady_clock::time_point start) const {
  const std::vector<PlacedObject>& objects = *view.objects;
  const SyntheticFrame frame = renderSyntheticFrame(
      objects, *view.colours, view.camera_pose, params_.camera, noise_,
      drawSceneLook(params_.look, params_.camera, view.look_seed), view.image_seed);
  const std::set<int> present = writeInstances(dataset_.sceneDir(view.scene), view.im, frame,
                                               objects, view.camera_pose, records);
  std::vector<HandleVisibility> handles =
      handleVisibility(frame, objects, view.camera_pose, handles_, params_.camera);
  if (!handles.empty()) records.handles[view.im] = std::move(handles);
  const SegmentationScene seen{frame.labels, objectIds(objects), frame.rgb, lookalikes_};
  const std::vector<BopTarget> targets = imageTargets(view, present, records.gt[view.im]);
  for (const BopTarget& t : targets) {
    const cv::Mat probability =
        simulateSegmentation(seen, t.obj_id, segmentation_, view.segmentation_seeds(t.obj_id));
    cv::Mat prob16;
    probability.convertTo(prob16, CV_16UC1, 10000.0);
    writeImage(dataset_.probabilityPath(view.scene, view.im, t.obj_id), prob16);
  }
  records.targets.insert(records.targets.end(), targets.begin(), targets.end());
  cv::Mat depth16;
  frame.depth.convertTo(depth16, CV_16UC1, 1000.0 / params_.depth_scale);
  writeImage(dataset_.depthPath(view.scene, view.im), depth16);
  writeImage(dataset_.rgbPath(view.scene, view.im), frame.rgb);
  records.cameras[view.im] = camera_;
  if (progress_) {
    progress_({view.scene, view.im, static_cast<int>(records.gt[view.im].size()),
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
  }
}

void SceneWriter::writeSceneFiles(int scene, const SceneRecords& records) const {
  const fs::path dir = dataset_.sceneDir(scene);
  writeSceneCameras(dir / "scene_camera.json", records.cameras);
  writeSceneGroundTruth(dir / "scene_gt.json", records.gt);
  writeSceneGtInfo(dir / "scene_gt_info.json", records.gt_info);
  if (!records.handles.empty()) writeSceneHandles(dir / "scene_handles.json", records.handles);
}

std::vector<BopTarget> SceneWriter::imageTargets(const SceneView& view,
                                                 const std::set<int>& present,
                                                 const std::vector<BopGtInstance>& gt) const {
  const std::set<int>& listed = view.listed ? *view.listed : present;
  std::vector<BopTarget> targets;
  for (int obj : listed) {
    const auto count = std::count_if(gt.begin(), gt.end(),
                                     [obj](const BopGtInstance& g) { return g.obj_id == obj; });
    targets.push_back({view.scene, view.im, obj, static_cast<int>(count)});
  }
  for (int obj : absentObjects(listed, view.absent_seed)) {
    targets.push_back({view.scene, view.im, obj, 0});
  }
  std::sort(targets.begin(), targets.end(),
            [](const BopTarget& a, const BopTarget& b) { return a.obj_id < b.obj_id; });
  return targets;
}

std::set<int> SceneWriter::absentObjects(const std::set<int>& present, uint64_t seed) const {
  std::vector<int> ids;
  for (const auto& [id, mesh] : models_) ids.push_back(id);
  return drawAbsentObjects(ids, present, params_.absent_per_image, seed, lookalikes_);
}

namespace {

/// Whether `id` has a look-alike among `present`.
bool looksLikeOneOf(int id, const std::set<int>& present, const Lookalikes& lookalikes) {
  const auto it = lookalikes.find(id);
  if (it == lookalikes.end()) return false;
  return std::any_of(it->second.begin(), it->second.end(),
                     [&](int other) { return present.count(other) > 0; });
}

/// Moves random members of `pool` into `absent` until it holds `count` or `pool` is empty.
void drawInto(std::vector<int>& pool, std::set<int>& absent, int count, Rng& rng) {
  while (static_cast<int>(absent.size()) < count && !pool.empty()) {
    const size_t k = uniformIndex(rng, static_cast<uint32_t>(pool.size()));
    absent.insert(pool[k]);
    pool.erase(pool.begin() + static_cast<long>(k));
  }
}

}  // namespace

std::set<int> drawAbsentObjects(const std::vector<int>& ids, const std::set<int>& present,
                                int count, uint64_t seed, const Lookalikes& lookalikes) {
  std::vector<int> fitting, spare;
  for (int id : ids) {
    if (present.count(id)) continue;
    (looksLikeOneOf(id, present, lookalikes) ? fitting : spare).push_back(id);
  }
  Rng rng(streamSeed(seed, 0xab5e47));
  std::set<int> absent;
  drawInto(fitting, absent, count, rng);
  drawInto(spare, absent, count, rng);
  return absent;
}

}  // namespace stocs
