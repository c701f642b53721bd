#pragma once
// Helpers shared by the tests: the real-data folder and small synthetic shapes with exact normals.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <string>
#include <vector>

#include "stocs/camera.h"
#include "stocs/mesh.h"

namespace cv {
class Mat;
}

namespace stocs::test {

/// The folder of real BOP datasets (env STOCS_DATASETS, else the CMake option). Returns an empty
/// path when neither is set; fails the test when it is set but missing, so a misconfigured CI
/// cannot pass by skipping.
std::filesystem::path datasetsDir();

/// Skips the current test when no data folder is configured at all (local runs without data).
#define STOCS_REQUIRE_DATASETS(var)                               \
  const std::filesystem::path var = ::stocs::test::datasetsDir(); \
  if (::testing::Test::HasFailure()) return;                      \
  if (var.empty()) GTEST_SKIP() << "STOCS_DATASETS is not set; real-data test skipped"

/// A fresh empty folder `name` under the current test's own scratch folder (removed first if it
/// exists).
std::filesystem::path scratchDir(const std::string& name);

/// Closed triangle mesh of an axis-aligned box centred at the origin (outward winding).
MeshData boxMesh(const Eigen::Vector3f& size);

/// Closed mesh of a surface of revolution about z through the (r, z) profile points (first and last
/// radius 0 close the ends), with `segments` around. Outward winding for a profile going upward on
/// the outside.
MeshData latheMesh(const std::vector<Eigen::Vector2f>& profile, int segments);

/// The 320 x 240 camera of the rendered test scenes (f = 300 px, principal point at the centre).
CameraIntrinsics testCamera();

struct PlacedMesh {
  MeshData mesh;
  Eigen::Isometry3f pose;  ///< mesh frame to camera
};

/// Depth (CV_32FC1, metres, 0 where nothing is seen) of meshes at poses by z-buffered splatting of
/// dense surface samples; `labels` (CV_32SC1) receives 1 + the index of the visible mesh, 0
/// elsewhere.
cv::Mat renderDepth(const std::vector<PlacedMesh>& objects, const CameraIntrinsics& camera,
                    cv::Mat* labels = nullptr);

/// An asymmetric test object: a 10 x 6 x 4 cm box with a 4 x 4 x 3 cm block on one corner of its
/// top.
MeshData asymmetricMesh();

/// A pose looking at an object `distance` metres in front of the camera, tilted so that three faces
/// of a box show.
Eigen::Isometry3f viewingPose(float distance);

/// Writes a one-image BOP dataset (scene 0, image 0, object 1 = asymmetricMesh in mm) rendered at
/// viewingPose(0.6) with a 16-bit probability map; returns the model-to-camera pose (metres).
Eigen::Isometry3f writeSyntheticBopDataset(const std::filesystem::path& root);

/// Runs a shell command, returning its exit code and capturing stdout and stderr in `output`.
int runCommand(const std::string& command, std::string& output);

/// Writes an ascii PLY with vertices (and faces when the mesh has triangles).
void writePly(const std::filesystem::path& file, const MeshData& mesh, float scale = 1.0f);

}  // namespace stocs::test
