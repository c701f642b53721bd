#pragma once
// The BOP results format: CSV with header scene_id,im_id,obj_id,score,R,t,time; R as 9 numbers
// (row-major) and t as 3 numbers (mm), space-separated; time in seconds for the whole image, the
// same on every row of an image, as the BOP toolkit requires.

#include <Eigen/Core>
#include <filesystem>
#include <vector>

namespace stocs {

struct BopResult {
  int scene_id = 0;
  int im_id = 0;
  int obj_id = 0;
  double score = 0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t_mm = Eigen::Vector3d::Zero();
  double time = -1;  ///< seconds; -1 when unknown
};

/// Writes atomically (temporary file, then rename). Throws InputError naming the file on failure.
void writeBopResults(const std::filesystem::path& file, const std::vector<BopResult>& results);

/// Reads a results file; throws InputError naming the file and line of any malformed row.
std::vector<BopResult> readBopResults(const std::filesystem::path& file);

}  // namespace stocs
