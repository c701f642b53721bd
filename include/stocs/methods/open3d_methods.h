#pragma once
// The Open3D baselines, a library of their own (stocs_methods_open3d) built only where Open3D is
// found, so that the core, the node and the ROS build never need it; a program that links the
// library has STOCS_HAVE_OPEN3D defined. Open3D's headers stay in the library's sources.

namespace stocs {

/// Adds "o3d-ransac" (FPFH features + RANSAC, Open3D's RegistrationRANSACBasedOnFeatureMatching)
/// and "o3d-fgr" (FPFH features + Fast Global Registration, Zhou et al. 2016) to the methods
/// `makeMethod` knows. Calling it again changes nothing.
void registerOpen3dMethods();

}  // namespace stocs
