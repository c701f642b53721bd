// "kfpcs": PCL's keypoint 4PCS (KFPCSInitialAlignment) on the hard segment. K4PCS runs 4PCS on
// keypoints and needs delta set to their precision (ia_kfpcs.hpp warns and ignores normalisation);
// PCL's own K4PCS test feeds voxel-grid keypoints with delta = the voxel size. The inputs here are
// exactly such points: the segment's voxel centroids and the model's even samples, the same points
// every method gets, with delta = the coarser of their spacings. Other parameters as fpcs (the
// table in four_pcs.cpp); the translation cost stays off (PCL default: no lower
// translation threshold), since nothing is known about the translation. Score: 1 - PCL's fitness,
// a truncated (MSAC) mean squared distance of up to 1000 model samples to the segment, in [0, 1].
#include <pcl/registration/ia_kfpcs.h>

#include "baseline_methods.h"
#include "four_pcs.h"

namespace stocs {
namespace {

using Kfpcs = pcl::registration::KFPCSInitialAlignment<pcl::PointXYZ, pcl::PointXYZ>;

/// K4PCS draws the model samples it validates candidates on right after PCL's clock seed, before
/// Reseeded can act; they are redrawn here from the run's seed, the same way (ia_kfpcs.hpp).
class SeededKfpcs : public Reseeded<Kfpcs> {
 public:
  using Reseeded<Kfpcs>::Reseeded;

 protected:
  bool initCompute() override {
    const bool ok = Reseeded<Kfpcs>::initCompute();
    const size_t n = indices_->size();
    if (n >= static_cast<size_t>(ransac_iterations_)) {
      indices_validation_->clear();
      for (int i = 0; i < ransac_iterations_; ++i) {
        indices_validation_->push_back((*indices_)[std::rand() % n]);
      }
    }
    return ok;
  }
};

class KfpcsMethod : public BaselineMethod {
 public:
  using BaselineMethod::BaselineMethod;
  std::string name() const override { return "kfpcs"; }

 protected:
  std::optional<BaselineHypothesis> search(const SoftSegment& segment,
                                           const ObjectInput& input) override {
    SeededKfpcs aligner(fourPcsSeed(input.params->stocs.seed));
    return alignFourPcs(aligner, segment, input);
  }
};

}  // namespace

std::unique_ptr<PoseMethod> makeKfpcsMethod(const MethodOptions& options) {
  return std::make_unique<KfpcsMethod>(options.hard_threshold);
}

}  // namespace stocs
