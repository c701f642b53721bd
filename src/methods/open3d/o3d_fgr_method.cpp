// "o3d-fgr": Open3D's Fast Global Registration (Zhou, Park and Koltun, ECCV 2016) on FPFH feature
// matches (FastGlobalRegistrationBasedOnFeatureMatching) between the model samples and the hard
// segment, with the clouds and features of fpfh_baseline.cpp. Parameters: Open3D 0.16's global
// registration tutorial (execute_fast_global_registration) sets only the maximum correspondence
// distance, 0.5 x voxel size; everything else is FastGlobalRegistrationOption's default (division
// factor 1.4, distances relative to the clouds' extent, decreasing mu, 64 iterations, tuple scale
// 0.95, at most 1000 tuples, tuple test on). With relative distances Open3D reads that distance
// relative to the clouds' extent while it optimises, and in metres for the fitness it reports; at
// the tutorial's 5 cm voxels it is the default, 0.025. No budget matches: FGR runs its 64
// iterations on the tuples it kept; --bases and --time-budget are not used.
#include <open3d/pipelines/registration/FastGlobalRegistration.h>

#include <stdexcept>

#include "fpfh_baseline.h"
#include "open3d_baselines.h"

namespace stocs {
namespace {

namespace reg = open3d::pipelines::registration;

constexpr double kCorrespondenceDistance = 0.5;  // x voxel size

class O3dFgrMethod : public FpfhBaselineMethod {
 public:
  using FpfhBaselineMethod::FpfhBaselineMethod;
  std::string name() const override { return "o3d-fgr"; }

 protected:
  reg::RegistrationResult align(const FpfhClouds& c) const override {
    reg::FastGlobalRegistrationOption option;
    option.maximum_correspondence_distance_ = kCorrespondenceDistance * c.voxel_size;
    try {
      return reg::FastGlobalRegistrationBasedOnFeatureMatching(
          c.model, c.segment, *c.model_features, *c.segment_features, option);
    } catch (const std::runtime_error&) {
      // Open3D 0.16's tuple test draws among the cross-checked matches with a generator that
      // throws when fewer than two passed the check: no registration, as with too few tuples.
      return reg::RegistrationResult();
    }
  }
};

}  // namespace

std::unique_ptr<PoseMethod> makeO3dFgrMethod(const MethodOptions& options) {
  return std::make_unique<O3dFgrMethod>(options.hard_threshold);
}

}  // namespace stocs
