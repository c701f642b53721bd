#pragma once
// Factories of the Open3D baselines, each defined in its own file; registered by
// registerOpen3dMethods() (open3d_methods.cpp).

#include <memory>

#include "stocs/methods/pose_method.h"

namespace stocs {

/// "o3d-ransac": FPFH features + open3d::pipelines::registration::
/// RegistrationRANSACBasedOnFeatureMatching.
std::unique_ptr<PoseMethod> makeO3dRansacMethod(const MethodOptions& options);

/// "o3d-fgr": FPFH features + open3d::pipelines::registration::
/// FastGlobalRegistrationBasedOnFeatureMatching (Zhou, Park and Koltun, ECCV 2016).
std::unique_ptr<PoseMethod> makeO3dFgrMethod(const MethodOptions& options);

}  // namespace stocs
