#pragma once
// Helpers shared by the tests: the real-data folder, scratch folders, rendering and a generated
// one-image dataset. Shapes come from the core (shape_meshes.h, object_catalogue.h).

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "stocs/geometry/camera.h"
#include "stocs/geometry/mesh.h"
#include "stocs/io/ply_writer.h"
#include "stocs/sim/object_catalogue.h"
#include "stocs/sim/shape_meshes.h"
#include "stocs/util/error.h"

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

struct PlacedMesh {
  MeshData mesh;
  Eigen::Isometry3f pose;  ///< mesh frame to camera
};

/// Depth (CV_32FC1, metres, 0 where nothing is seen) of meshes at poses by z-buffered splatting of
/// dense surface samples; `labels` (CV_32SC1) receives 1 + the index of the visible mesh, 0
/// elsewhere.
cv::Mat renderDepth(const std::vector<PlacedMesh>& objects, const CameraIntrinsics& camera,
                    cv::Mat* labels = nullptr);

/// A 160 x 120 camera with a 200 px focal length, for small renders.
CameraIntrinsics smallCamera();

/// The 320 x 240 pinhole camera (f = 300 px) of the rendered test scenes.
CameraIntrinsics testCamera();

/// A pose looking at an object `distance` metres in front of the camera, tilted so that three faces
/// of a box show.
Eigen::Isometry3f viewingPose(float distance);

/// Writes a one-image BOP dataset (scene 0, image 0, object 1 = asymmetricMesh in mm) rendered at
/// viewingPose(0.6) with a 16-bit probability map; returns the model-to-camera pose (metres).
Eigen::Isometry3f writeSyntheticBopDataset(const std::filesystem::path& root);

/// Writes a generated BOP dataset of one image holding 3 objects and a distractor (seed 11).
void writeThreeObjectScene(const std::filesystem::path& root);

/// The bytes of `file`.
std::string fileBytes(const std::filesystem::path& file);

/// Every file below `root`, relative to it, with its bytes: for comparing generated datasets.
std::map<std::string, std::string> treeFiles(const std::filesystem::path& root);

/// Rows of a CSV file (no quoted commas, as the tools write them) as column name -> value; the
/// first line names the columns.
std::vector<std::map<std::string, std::string>> readCsv(const std::filesystem::path& file);

/// Runs a shell command, returning its exit code and capturing stdout and stderr in `output`.
int runCommand(const std::string& command, std::string& output);

/// Expects `f()` to throw InputError with a message holding `part`.
template <class F>
void expectInputError(F f, const std::string& part) {
  try {
    f();
    ADD_FAILURE() << "no InputError; expected one holding '" << part << "'";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

}  // namespace stocs::test
