#include "stocs/soft_segment.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <unordered_map>

#include "stocs/error.h"
#include "stocs/voxel_key.h"

namespace stocs {
namespace {

struct Voxel {
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  double probability_sum = 0;
  int count = 0;
};

}  // namespace

void SoftSegmentParams::validate() const {
  if (!(min_probability >= 0.0f && min_probability < 1.0f)) {
    throw InputError(
        fmt::format("segment probability threshold {} is outside [0, 1)", min_probability));
  }
  if (!(voxel_size >= 0.0f && voxel_size <= 0.1f)) {
    throw InputError(fmt::format("segment voxel size {} m is outside [0, 0.1]", voxel_size));
  }
  if (!(normals.radius > 0.0f && normals.radius <= 0.2f)) {
    throw InputError(fmt::format("normal radius {} m is outside (0, 0.2]", normals.radius));
  }
  if (normals.samples_per_axis < 3 || normals.min_neighbours < 3) {
    throw InputError("normal estimation needs at least 3 samples per axis and 3 neighbours");
  }
}

SoftSegment buildSoftSegment(const OrganizedCloud& cloud, const cv::Mat& probability,
                             float focal_px, const SoftSegmentParams& params, int threads) {
  params.validate();
  if (probability.type() != CV_32FC1) {
    throw InputError("probability image must be CV_32FC1 (use toProbabilityImage)");
  }
  if (probability.cols != cloud.width || probability.rows != cloud.height) {
    throw InputError(fmt::format("probability image is {}x{} but the cloud is {}x{}",
                                 probability.cols, probability.rows, cloud.width, cloud.height));
  }
  if (!(focal_px > 0) || !std::isfinite(focal_px)) {
    throw InputError(fmt::format("focal length {} px is not positive", focal_px));
  }

  // Pass 1: group the pixels above epsilon by voxel (each pixel is its own group at voxel size 0).
  // A voxel spans several pixels, so the key of the pixel to the left or above is usually the
  // same: remembering their groups skips most hash lookups, each of which costs an integer
  // division by the table's prime size. A remembered key always maps to its group.
  const float inv = params.voxel_size > 0 ? 1.0f / params.voxel_size : 0.0f;
  constexpr uint64_t kNoKey = ~uint64_t{0};  // packVoxelCell never sets the top bit
  std::unordered_map<uint64_t, int> group_of_key;
  uint64_t left_key = kNoKey;
  int left_group = -1;
  std::vector<uint64_t> above_key(static_cast<size_t>(cloud.width), kNoKey);
  std::vector<int> above_group(static_cast<size_t>(cloud.width), -1);
  struct KeptPixel {
    int pixel, group;
  };
  std::vector<KeptPixel> kept;  // in image order
  std::vector<Voxel> groups;
  const float threshold = params.min_probability;
  for (int v = 0; v < cloud.height; ++v) {
    const float* prob_row = probability.ptr<float>(v);
    auto visit = [&](int u) {
      const float p = prob_row[u];
      const int i = v * cloud.width + u;
      if (!(p > threshold) || !cloud.isValid(i)) return;
      int g = static_cast<int>(groups.size());
      if (inv > 0) {
        const uint64_t key = packVoxelCell(voxelCell(cloud.points[i], inv));
        if (key == left_key) {
          g = left_group;
        } else if (key == above_key[u]) {
          g = above_group[u];
        } else {
          g = group_of_key.try_emplace(key, g).first->second;
        }
        left_key = above_key[u] = key;
        left_group = above_group[u] = g;
      }
      if (g == static_cast<int>(groups.size())) groups.emplace_back();
      Voxel& vox = groups[g];
      vox.sum += cloud.points[i];
      vox.probability_sum += p;
      ++vox.count;
      kept.push_back({i, g});
    };
    // Most of an image is background, below epsilon: a block of 16 pixels with none above it is
    // skipped after 16 branch-free comparisons (a test and a branch per pixel cost 10
    // instructions, 3 M per 640x480 image, a fifth of the cat's soft segment).
    constexpr int kBlock = 16;
    int u = 0;
    for (; u + kBlock <= cloud.width; u += kBlock) {
      int any = 0;
      for (int k = 0; k < kBlock; ++k) any |= prob_row[u + k] > threshold;
      if (!any) continue;
      for (int k = 0; k < kBlock; ++k) visit(u + k);
    }
    for (; u < cloud.width; ++u) visit(u);
  }
  // Pass 2: the representative of a group is its pixel nearest the centroid, which lies on the
  // surface even when the centroid of a voxel straddling a depth edge does not.
  std::vector<int> representative(groups.size(), -1);
  std::vector<float> best_d2(groups.size(), std::numeric_limits<float>::max());
  for (const KeptPixel& k : kept) {
    const Voxel& vox = groups[k.group];
    const float d2 =
        (cloud.points[k.pixel] - vox.sum / static_cast<float>(vox.count)).squaredNorm();
    if (d2 < best_d2[k.group]) {
      best_d2[k.group] = d2;
      representative[k.group] = k.pixel;
    }
  }

  std::vector<Eigen::Vector3f> normals(groups.size());
  const auto group_count = static_cast<std::ptrdiff_t>(groups.size());
#pragma omp parallel for num_threads(std::max(1, threads)) schedule(static)
  for (std::ptrdiff_t g = 0; g < group_count; ++g) {
    normals[g] = organizedNormal(cloud, representative[g], focal_px, params.normals);
  }

  SoftSegment segment;
  double total = 0;
  for (size_t g = 0; g < groups.size(); ++g) {  // groups are in order of first pixel: deterministic
    const Eigen::Vector3f& normal = normals[g];
    if (!normal.allFinite()) continue;
    const Voxel& vox = groups[g];
    segment.points.push_back(vox.sum / static_cast<float>(vox.count));
    segment.normals.push_back(normal);
    segment.confidence.push_back(static_cast<float>(vox.probability_sum / vox.count));
    segment.pixel.push_back(representative[g]);
    total += segment.confidence.back();
  }
  segment.probability.reserve(segment.size());
  for (float c : segment.confidence) segment.probability.push_back(static_cast<float>(c / total));
  return segment;
}

void labelRegions(SoftSegment& segment, const cv::Mat& boundary_map, int width, int height) {
  if (boundary_map.type() != CV_8UC1) {
    throw InputError(
        "boundary map must be a single-channel 8-bit image (255 interior, 0 boundary)");
  }
  if (boundary_map.cols != width || boundary_map.rows != height) {
    throw InputError(fmt::format("boundary map is {}x{} but the image is {}x{}", boundary_map.cols,
                                 boundary_map.rows, width, height));
  }
  cv::Mat interior = boundary_map >= 128;
  cv::Mat labels;
  cv::connectedComponents(interior, labels, 4, CV_32S);
  segment.region.resize(segment.size());
  for (size_t i = 0; i < segment.size(); ++i) {
    const int label = labels.at<int>(segment.pixel[i] / width, segment.pixel[i] % width);
    segment.region[i] = label > 0 ? label : -1;  // component 0 is the boundary itself
  }
}

}  // namespace stocs
