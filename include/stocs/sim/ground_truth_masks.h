#pragma once
// The visible ground-truth instances of a BOP frame as the segmentation simulator needs them: from
// the frame's `mask_visib/` when it has one for every instance, else by rendering every
// ground-truth model of the frame at its pose in one z-buffer, so that they occlude each other.

#include <map>

#include "stocs/geometry/mesh.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/sim/segmentation_simulator.h"

namespace stocs {

class GroundTruthMasks {
 public:
  /// Keeps a reference: `dataset` must outlive this object. Throws InputError for a malformed
  /// models/lookalikes.json.
  explicit GroundTruthMasks(const BopDataset& dataset);

  /// Labels (1 + index of the instance in scene_gt.json, 0 for none), the object id of each
  /// instance, the RGB image when the frame has one, and the dataset's look-alike pairs
  /// (models/lookalikes.json, lookalikes.h). Throws InputError naming the file of a
  /// missing or malformed input.
  SegmentationScene frame(int scene_id, int im_id) const;

  /// Whether the visible masks of the frame come from `mask_visib/` (else they are rendered).
  bool hasMaskVisib(int scene_id, int im_id, size_t instances) const;

 private:
  /// A ground-truth model in metres, loaded once.
  const MeshData& model(int obj_id) const;

  const BopDataset& dataset_;
  const std::map<int, std::set<int>> lookalikes_;
  mutable std::map<int, MeshData> models_;
  mutable std::map<int, float> splat_radius_;  ///< for point models, metres
};

}  // namespace stocs
