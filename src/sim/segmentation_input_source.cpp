#include "stocs/sim/segmentation_input_source.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "stocs/io/box_files.h"
#include "stocs/sim/detection_perturbation.h"
#include "stocs/sim/ground_truth_masks.h"
#include "stocs/util/error.h"
#include "stocs/util/random.h"

namespace stocs {
namespace {

enum class Form { kLabels, kMasks, kBoxes };

const std::vector<std::pair<std::string, Form>> kForms = {
    {"labels", Form::kLabels}, {"masks", Form::kMasks}, {"boxes", Form::kBoxes}};
const char* const kPerturbedPreset = "mild";

/// The random stream of one object of one frame: the simulator's, so that masks:PRESET
/// thresholds the very map sim:PRESET gives.
uint64_t objectKey(int scene_id, int im_id, int obj_id) {
  return (static_cast<uint64_t>(scene_id) << 40) ^ (static_cast<uint64_t>(im_id) << 20) ^
         static_cast<uint64_t>(obj_id);
}

/// One form of detections with how they were made.
struct SourceSpec {
  Form form = Form::kMasks;
  std::optional<SegmentationNoiseParams> perturbation;  ///< masks, labels: the simulator's preset
  bool perturb_boxes = false;
  std::optional<FrameBoxes> file_boxes;  ///< boxes:FILE
};

/// Throws InputError for a box of a class the dataset has no model of.
void checkBoxClasses(const FrameBoxes& boxes, const std::string& file, const BopDataset& dataset) {
  for (const auto& [frame, detections] : boxes) {
    for (const BoxDetection& d : detections) {
      if (!dataset.hasModel(d.class_id)) {
        throw InputError(fmt::format(
            "{}: scene {} image {} has a box of category_id {}, which is not an object of the "
            "dataset (no {})",
            file, frame.first, frame.second, d.class_id, dataset.modelPath(d.class_id).string()));
      }
    }
  }
}

SourceSpec parseSpec(const std::string& spec, const BopDataset& dataset) {
  const size_t colon = spec.find(':');
  const std::string name = spec.substr(0, colon);
  const auto form =
      std::find_if(kForms.begin(), kForms.end(), [&](const auto& f) { return f.first == name; });
  if (form == kForms.end()) throw InputError(fmt::format("unknown segmentation input '{}'", spec));
  SourceSpec s;
  s.form = form->second;
  if (colon == std::string::npos) return s;
  const std::string variant = spec.substr(colon + 1);
  if (s.form == Form::kBoxes) {
    if (variant == "perturbed") {
      s.perturb_boxes = true;
    } else {
      s.file_boxes = readBoxDetections(variant);
      checkBoxClasses(*s.file_boxes, variant, dataset);
    }
    return s;
  }
  s.perturbation = segmentationPreset(variant == "perturbed" ? kPerturbedPreset : variant);
  return s;
}

/// Every mask of object `obj` in a frame, with score 1.
std::vector<InstanceMask> groundTruthMasks(const SegmentationScene& scene, int obj) {
  std::vector<InstanceMask> masks;
  for (size_t i = 0; i < scene.obj_ids.size(); ++i) {
    if (scene.obj_ids[i] != obj) continue;
    InstanceMask m{scene.labels == static_cast<int>(i) + 1, obj, 1.0f};
    if (cv::countNonZero(m.mask) > 0) masks.push_back(std::move(m));
  }
  return masks;
}

/// A label image (CV_16UC1, object id per pixel) painted from masks, the higher score on top.
cv::Mat paintLabels(std::vector<InstanceMask> masks, cv::Size size) {
  std::stable_sort(masks.begin(), masks.end(),
                   [](const InstanceMask& a, const InstanceMask& b) { return a.score < b.score; });
  cv::Mat labels(size, CV_16UC1, cv::Scalar(0));
  for (const InstanceMask& m : masks) labels.setTo(m.class_id, m.mask);
  return labels;
}

}  // namespace

/// The detections of one frame at a time, each part made when first asked for.
class SegmentationInputSource::Frames {
 public:
  Frames(std::string spec, const BopDataset& dataset, uint64_t seed,
         const SegmentationInputParams& params)
      : spec_(std::move(spec)),
        parsed_(parseSpec(spec_, dataset)),
        dataset_(dataset),
        masks_(dataset),
        seed_(seed),
        params_(params) {
    params_.validate();
  }

  const std::string& spec() const { return spec_; }
  Form form() const { return parsed_.form; }
  const BopDataset& dataset() const { return dataset_; }
  const SegmentationInputParams& params() const { return params_; }

  void selectFrame(int scene_id, int im_id) {
    if (frame_.scene_id == scene_id && frame_.im_id == im_id) return;
    frame_ = FrameCache();
    frame_.scene_id = scene_id;
    frame_.im_id = im_id;
    frame_.size = dataset_.loadDepth(scene_id, im_id).size();
  }

  cv::Size size() const { return frame_.size; }

  const std::vector<InstanceMask>& masksOf(int obj_id) {
    auto it = frame_.masks.find(obj_id);
    if (it != frame_.masks.end()) return it->second;
    const uint64_t seed = streamSeed(seed_, objectKey(frame_.scene_id, frame_.im_id, obj_id));
    auto masks = parsed_.perturbation ? perturbedMasks(scene(), obj_id, *parsed_.perturbation, seed)
                                      : groundTruthMasks(scene(), obj_id);
    return frame_.masks.emplace(obj_id, std::move(masks)).first->second;
  }

  const cv::Mat& labels() {
    if (frame_.labels.empty()) {
      std::vector<InstanceMask> all;
      std::vector<int> objects = scene().obj_ids;
      std::sort(objects.begin(), objects.end());
      objects.erase(std::unique(objects.begin(), objects.end()), objects.end());
      for (int obj : objects) {
        const auto& masks = masksOf(obj);
        all.insert(all.end(), masks.begin(), masks.end());
      }
      frame_.labels = paintLabels(std::move(all), size());
    }
    return frame_.labels;
  }

  const std::vector<BoxDetection>& boxes() {
    if (!frame_.boxes) {
      if (parsed_.file_boxes) {
        const auto it = parsed_.file_boxes->find({frame_.scene_id, frame_.im_id});
        frame_.boxes = it == parsed_.file_boxes->end() ? std::vector<BoxDetection>() : it->second;
      } else {
        frame_.boxes = groundTruthBoxes();
      }
    }
    return *frame_.boxes;
  }

 private:
  /// What is kept of the current frame, each part made when first asked for.
  struct FrameCache {
    int scene_id = -1, im_id = -1;
    std::optional<SegmentationScene> scene;
    std::map<int, std::vector<InstanceMask>> masks;  ///< by object id
    cv::Mat labels;
    std::optional<std::vector<BoxDetection>> boxes;
    cv::Size size;
  };

  /// The frame's visible ground-truth masks; a mask_visib/ folder missing an instance's file is
  /// an error rather than a reason to render.
  const SegmentationScene& scene() {
    if (!frame_.scene) {
      const int scene_id = frame_.scene_id, im_id = frame_.im_id;
      const size_t instances = dataset_.sceneGroundTruth(scene_id).at(im_id).size();
      std::error_code ec;
      if (std::filesystem::is_directory(dataset_.sceneDir(scene_id) / "mask_visib", ec)) {
        for (size_t i = 0; i < instances; ++i) {
          const auto file = dataset_.maskVisibPath(scene_id, im_id, static_cast<int>(i));
          if (!std::filesystem::exists(file, ec)) {
            throw InputError(
                fmt::format("{}: no such file (scene_gt.json has {} instances in image {})",
                            file.string(), instances, im_id));
          }
        }
      }
      frame_.scene = masks_.frame(scene_id, im_id);
    }
    return *frame_.scene;
  }

  /// Each visible instance's box (scene_gt_info.json, else its mask's bounding box), perturbed
  /// with boxes:perturbed.
  std::vector<BoxDetection> groundTruthBoxes() {
    const int scene_id = frame_.scene_id, im_id = frame_.im_id;
    const std::vector<BopGtInstance> gt = dataset_.sceneGroundTruth(scene_id).at(im_id);
    const std::vector<cv::Rect2f> visible = visibleBoxes(gt.size());
    std::vector<BoxDetection> boxes;
    for (size_t i = 0; i < gt.size(); ++i) {
      if (!(visible[i].width > 0 && visible[i].height > 0)) continue;
      BoxDetection b{visible[i], gt[i].obj_id, 1.0f};
      if (parsed_.perturb_boxes) {
        b = perturbedBox(b, streamSeed(seed_, objectKey(scene_id, im_id, gt[i].obj_id) ^
                                                  (static_cast<uint64_t>(i) << 56)));
      }
      boxes.push_back(b);
    }
    return boxes;
  }

  std::vector<cv::Rect2f> visibleBoxes(size_t instances) {
    const int scene_id = frame_.scene_id, im_id = frame_.im_id;
    const auto info = dataset_.sceneDir(scene_id) / "scene_gt_info.json";
    std::error_code ec;
    if (!std::filesystem::exists(info, ec)) {
      std::vector<cv::Rect2f> boxes;
      for (size_t i = 0; i < instances; ++i) {
        boxes.emplace_back(cv::boundingRect(scene().labels == static_cast<int>(i) + 1));
      }
      return boxes;
    }
    const auto all = readVisibleBoxes(info);
    const auto it = all.find(im_id);
    if (it == all.end() || it->second.size() != instances) {
      throw InputError(fmt::format("{}: image {} has {} instances, scene_gt.json {}", info.string(),
                                   im_id, it == all.end() ? 0 : it->second.size(), instances));
    }
    return it->second;
  }

  std::string spec_;
  SourceSpec parsed_;
  const BopDataset& dataset_;
  GroundTruthMasks masks_;
  uint64_t seed_;
  SegmentationInputParams params_;
  FrameCache frame_;
};

SegmentationInputSource::SegmentationInputSource(const std::string& spec, const BopDataset& dataset,
                                                 uint64_t seed,
                                                 const SegmentationInputParams& params)
    : frames_(std::make_unique<Frames>(spec, dataset, seed, params)) {}

SegmentationInputSource::~SegmentationInputSource() = default;

std::string SegmentationInputSource::spec() const {
  return frames_->spec();
}

bool SegmentationInputSource::available(int, int, int obj_id) const {
  return frames_->dataset().hasModel(obj_id);
}

cv::Mat SegmentationInputSource::load(int scene_id, int im_id, int obj_id) const {
  frames_->selectFrame(scene_id, im_id);
  const SegmentationInputParams& params = frames_->params();
  switch (frames_->form()) {
    case Form::kLabels:
      return labelProbability(frames_->labels(), cv::Mat(), obj_id, params);
    case Form::kMasks:
      return maskProbability(frames_->masksOf(obj_id), obj_id, frames_->size(), params);
    case Form::kBoxes:
      return boxProbability(frames_->boxes(), obj_id, frames_->size(), params);
  }
  return {};
}

std::string SegmentationInputSource::form() const {
  for (const auto& [name, form] : kForms) {
    if (form == frames_->form()) return name;
  }
  return {};
}

cv::Mat SegmentationInputSource::labels(int scene_id, int im_id) const {
  frames_->selectFrame(scene_id, im_id);
  return frames_->labels();
}

std::vector<InstanceMask> SegmentationInputSource::masks(int scene_id, int im_id,
                                                         const std::vector<int>& obj_ids) const {
  frames_->selectFrame(scene_id, im_id);
  std::vector<InstanceMask> all;
  for (int obj : obj_ids) {
    const auto& masks = frames_->masksOf(obj);
    all.insert(all.end(), masks.begin(), masks.end());
  }
  return all;
}

std::vector<BoxDetection> SegmentationInputSource::boxes(int scene_id, int im_id) const {
  frames_->selectFrame(scene_id, im_id);
  return frames_->boxes();
}

bool isSegmentationInputSpec(const std::string& spec) {
  const std::string name = spec.substr(0, spec.find(':'));
  return std::any_of(kForms.begin(), kForms.end(), [&](const auto& f) { return f.first == name; });
}

std::string segmentationInputHelp() {
  return fmt::format(
      "'masks', 'labels', 'boxes' (from the ground truth: mask_visib/, scene_gt_info.json), "
      "'masks:perturbed', 'labels:perturbed' (as a network errs: the simulator's {} preset; or "
      "masks:PRESET, labels:PRESET), 'boxes:perturbed' (shifted, loose, score noise) or "
      "'boxes:FILE' (BOP 2D detections JSON)",
      kPerturbedPreset);
}

std::unique_ptr<ProbabilitySource> makeSegmentationInputSource(
    const std::string& spec, const BopDataset& dataset, uint64_t seed,
    const SegmentationInputParams& params) {
  return std::make_unique<SegmentationInputSource>(spec, dataset, seed, params);
}

}  // namespace stocs
