#include "stocs/sim/probability_source.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <opencv2/core.hpp>
#include <optional>
#include <utility>

#include "geometric_probability_source.h"
#include "network_probability_source.h"
#include "stocs/sim/ground_truth_masks.h"
#include "stocs/sim/segmentation_input_source.h"
#include "stocs/sim/segmentation_simulator.h"
#include "stocs/util/error.h"
#include "stocs/util/random.h"

namespace stocs {
namespace {

bool hasRealMap(const BopDataset& dataset, int scene_id, int im_id, int obj_id) {
  std::error_code ec;
  return std::filesystem::exists(dataset.probabilityPath(scene_id, im_id, obj_id), ec);
}

/// The network maps shipped with the dataset (`prob/{im}_{obj}.png`).
class RealProbabilitySource : public ProbabilitySource {
 public:
  explicit RealProbabilitySource(const BopDataset& dataset) : dataset_(dataset) {}
  std::string spec() const override { return "real"; }
  bool available(int scene_id, int im_id, int obj_id) const override {
    return hasRealMap(dataset_, scene_id, im_id, obj_id);
  }
  cv::Mat load(int scene_id, int im_id, int obj_id) const override {
    return dataset_.loadProbability(scene_id, im_id, obj_id);
  }

 private:
  const BopDataset& dataset_;
};

/// No segmentation: every pixel of the frame is the object's (probability 1), for any object with
/// a model: the registration methods on the whole scene.
class WholeSceneSource : public ProbabilitySource {
 public:
  explicit WholeSceneSource(const BopDataset& dataset) : dataset_(dataset) {}
  std::string spec() const override { return "whole"; }
  bool namesObjects() const override { return false; }
  bool available(int, int, int obj_id) const override { return dataset_.hasModel(obj_id); }
  cv::Mat load(int scene_id, int im_id, int) const override {
    const std::pair<int, int> image{scene_id, im_id};
    if (image != image_) {  // the depth is read once per image, for its size
      size_ = dataset_.loadDepth(scene_id, im_id).size();
      image_ = image;
    }
    return cv::Mat(size_, CV_32FC1, cv::Scalar(1));
  }

 private:
  const BopDataset& dataset_;
  mutable std::pair<int, int> image_{-1, -1};
  mutable cv::Size size_;
};

/// The segmentation simulator on the frame's visible ground-truth masks, for every object of the
/// dataset (one without ground truth in the frame gets the simulator's absent-object map); with
/// `prefer_real`, the real map wherever the dataset has one.
class SimulatedProbabilitySource : public ProbabilitySource {
 public:
  SimulatedProbabilitySource(std::string spec, const BopDataset& dataset,
                             SegmentationNoiseParams params, uint64_t seed, bool prefer_real)
      : spec_(std::move(spec)),
        dataset_(dataset),
        masks_(dataset),
        params_(params),
        seed_(seed),
        prefer_real_(prefer_real) {}

  std::string spec() const override { return spec_; }

  bool available(int scene_id, int im_id, int obj_id) const override {
    return (prefer_real_ && hasRealMap(dataset_, scene_id, im_id, obj_id)) ||
           dataset_.hasModel(obj_id);
  }

  cv::Mat load(int scene_id, int im_id, int obj_id) const override {
    if (prefer_real_ && hasRealMap(dataset_, scene_id, im_id, obj_id)) {
      return dataset_.loadProbability(scene_id, im_id, obj_id);
    }
    // One random stream per (scene, image, object): a map does not depend on what else was asked.
    const uint64_t key = (static_cast<uint64_t>(scene_id) << 40) ^
                         (static_cast<uint64_t>(im_id) << 20) ^ static_cast<uint64_t>(obj_id);
    return simulateSegmentation(frame(scene_id, im_id), obj_id, params_, streamSeed(seed_, key));
  }

 private:
  /// The frame's masks, kept for the objects that follow (one frame at a time).
  const SegmentationScene& frame(int scene_id, int im_id) const {
    if (!cached_ || cached_->first != std::make_pair(scene_id, im_id)) {
      cached_.emplace(std::make_pair(scene_id, im_id), masks_.frame(scene_id, im_id));
    }
    return cached_->second;
  }

  std::string spec_;
  const BopDataset& dataset_;
  GroundTruthMasks masks_;
  SegmentationNoiseParams params_;
  uint64_t seed_;
  bool prefer_real_;
  mutable std::optional<std::pair<std::pair<int, int>, SegmentationScene>> cached_;
};

}  // namespace

std::string probabilitySourceHelp() {
  return fmt::format(
      "'real' (the dataset's prob/ maps), 'sim:PRESET' (real maps where prob/ has one, the "
      "segmentation simulator on the ground-truth masks elsewhere) or 'simonly:PRESET' (always "
      "simulated), 'onnx:MODEL' (the segmentation network MODEL on the rgb/ images: an ONNX file "
      "with the package network's settings, or a settings YAML naming one), 'geometric' (from the "
      "depth alone: regions left when the supporting planes and the depth edges are removed, "
      "those of the object's size), 'whole' (no segmentation: the whole scene, every pixel 1); "
      "presets: {}; "
      "segmentation inputs: {}",
      fmt::join(segmentationPresetNames(), ", "), segmentationInputHelp());
}

std::unique_ptr<ProbabilitySource> makeProbabilitySource(const std::string& spec,
                                                         const BopDataset& dataset, uint64_t seed) {
  if (spec == "real") return std::make_unique<RealProbabilitySource>(dataset);
  if (spec == "geometric") return makeGeometricProbabilitySource(dataset);
  if (spec == "whole") return std::make_unique<WholeSceneSource>(dataset);
  if (spec.rfind("onnx:", 0) == 0)
    return makeNetworkProbabilitySource(spec, spec.substr(5), dataset);
  if (isSegmentationInputSpec(spec)) return makeSegmentationInputSource(spec, dataset, seed);
  for (const auto& [prefix, prefer_real] :
       {std::pair{"sim:", true}, std::pair{"simonly:", false}}) {
    const std::string p = prefix;
    if (spec.rfind(p, 0) == 0) {
      return std::make_unique<SimulatedProbabilitySource>(
          spec, dataset, segmentationPreset(spec.substr(p.size())), seed, prefer_real);
    }
  }
  throw InputError(
      fmt::format("unknown probability source '{}'; known: {}", spec, probabilitySourceHelp()));
}

}  // namespace stocs
