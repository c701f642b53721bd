#pragma once
// Factories of the baseline methods, each defined in its own file so that the heavy PCL and OpenCV
// contrib headers stay inside src/methods/*.cpp.

#include <memory>

#include "stocs/methods/pose_method.h"

namespace stocs {

/// "fpcs": pcl::registration::FPCSInitialAlignment (4PCS, Aiger et al. 2008).
std::unique_ptr<PoseMethod> makeFpcsMethod(const MethodOptions& options);

/// "kfpcs": pcl::registration::KFPCSInitialAlignment (keypoint 4PCS, Theiler et al. 2013).
std::unique_ptr<PoseMethod> makeKfpcsMethod(const MethodOptions& options);

/// "ppf": cv::ppf_match_3d::PPF3DDetector (PPF Hough voting, Drost et al. 2010).
std::unique_ptr<PoseMethod> makePpfMethod(const MethodOptions& options);

}  // namespace stocs
