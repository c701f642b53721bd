#pragma once
// Probability maps of a BOP frame made from the segmentation forms a robot may have instead of
// probability maps: a label image, instance masks or 2D boxes (segmentation_inputs.h), taken from
// the frame's ground truth, perturbed the way a real network errs, or (boxes) read from a
// detector's file. `stocs estimate --prob masks:perturbed` and `stocs bench` select them.

#include <memory>
#include <string>

#include "stocs/io/segmentation_inputs.h"
#include "stocs/sim/probability_source.h"

namespace stocs {

/// Whether `spec` names a segmentation input form ("labels", "masks", "boxes", with a suffix).
bool isSegmentationInputSpec(const std::string& spec);

/// What the specs mean, for help texts.
std::string segmentationInputHelp();

/// "masks": each visible ground-truth instance's mask (mask_visib/, else rendered as
/// GroundTruthMasks does) with score 1; "masks:perturbed" (the simulator's `mild` preset) or
/// "masks:PRESET": perturbedMasks; "labels", "labels:perturbed", "labels:PRESET": a label image
/// painted from those masks, the higher score on top; "boxes": scene_gt_info.json's bbox_visib
/// (else each visible mask's bounding box) with score 1; "boxes:perturbed": each perturbedBox;
/// "boxes:FILE": a detector's boxes in the BOP 2D detection format (box_files.h). Each turned into
/// maps with `params`. Throws InputError for an unknown spec or preset, or a malformed boxes file;
/// load() throws InputError naming a missing mask file, a size mismatch or a malformed
/// scene_gt_info.json. Keeps the last frame's detections: not for several threads at once.
std::unique_ptr<ProbabilitySource> makeSegmentationInputSource(
    const std::string& spec, const BopDataset& dataset, uint64_t seed,
    const SegmentationInputParams& params = {});

/// The source makeSegmentationInputSource makes, with the detections themselves for a publisher of
/// them (the scene publisher): each call as load() makes them, errors as load()'s.
class SegmentationInputSource : public ProbabilitySource {
 public:
  SegmentationInputSource(const std::string& spec, const BopDataset& dataset, uint64_t seed,
                          const SegmentationInputParams& params = {});
  ~SegmentationInputSource() override;

  std::string spec() const override;
  bool available(int scene_id, int im_id, int obj_id) const override;
  cv::Mat load(int scene_id, int im_id, int obj_id) const override;

  /// "labels", "masks" or "boxes".
  std::string form() const;
  /// The label image (CV_16UC1, object id per pixel, 0 for none).
  cv::Mat labels(int scene_id, int im_id) const;
  /// The instance masks of the objects `obj_ids`.
  std::vector<InstanceMask> masks(int scene_id, int im_id, const std::vector<int>& obj_ids) const;
  std::vector<BoxDetection> boxes(int scene_id, int im_id) const;

 private:
  class Frames;
  std::unique_ptr<Frames> frames_;
};

}  // namespace stocs
