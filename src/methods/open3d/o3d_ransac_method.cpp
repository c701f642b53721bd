// "o3d-ransac": Open3D's RANSAC on FPFH feature matches (RegistrationRANSACBasedOnFeatureMatching)
// between the model samples and the hard segment, with the clouds and features of
// fpfh_baseline.cpp. Parameters, all those of Open3D 0.16's global registration tutorial
// (execute_global_registration), whose RANSAC values it takes from Choi, Zhou and Koltun (CVPR
// 2015):
//   correspondence distance  1.5 x voxel size ("a liberal distance threshold")
//   mutual filter            on (a match's match must be the point itself)
//   estimation               point to point, no scaling; 3 correspondences per hypothesis
//   checkers                 edge length 0.9 (edges of the 3 points alike within 10%), distance
//                            (the correspondence distance)
//   convergence              at most 100000 hypotheses, stop at confidence 0.999 (the defaults)
// No budget matches: a RANSAC iteration is one 3-point hypothesis, not a base with its congruent
// sets, and Open3D 0.16 has no time limit; --bases and --time-budget are not used.
#include <open3d/pipelines/registration/CorrespondenceChecker.h>
#include <open3d/pipelines/registration/TransformationEstimation.h>

#include "fpfh_baseline.h"
#include "open3d_baselines.h"

namespace stocs {
namespace {

namespace reg = open3d::pipelines::registration;

constexpr double kCorrespondenceDistance = 1.5;  // x voxel size
constexpr bool kMutualFilter = true;
constexpr int kRansacN = 3;
constexpr double kEdgeSimilarity = 0.9;
constexpr int kMaxIterations = 100000;
constexpr double kConfidence = 0.999;

class O3dRansacMethod : public FpfhBaselineMethod {
 public:
  using FpfhBaselineMethod::FpfhBaselineMethod;
  std::string name() const override { return "o3d-ransac"; }

 protected:
  reg::RegistrationResult align(const FpfhClouds& c) const override {
    const double distance = kCorrespondenceDistance * c.voxel_size;
    const reg::CorrespondenceCheckerBasedOnEdgeLength edges(kEdgeSimilarity);
    const reg::CorrespondenceCheckerBasedOnDistance near(distance);
    return reg::RegistrationRANSACBasedOnFeatureMatching(
        c.model, c.segment, *c.model_features, *c.segment_features, kMutualFilter, distance,
        reg::TransformationEstimationPointToPoint(false), kRansacN, {edges, near},
        reg::RANSACConvergenceCriteria(kMaxIterations, kConfidence));
  }
};

}  // namespace

std::unique_ptr<PoseMethod> makeO3dRansacMethod(const MethodOptions& options) {
  return std::make_unique<O3dRansacMethod>(options.hard_threshold);
}

}  // namespace stocs
