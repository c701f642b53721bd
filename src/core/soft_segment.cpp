#include "stocs/soft_segment.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <unordered_map>

#include "stocs/boundary_regions.h"
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
  if (!(samples_per_voxel == 0.0f || (samples_per_voxel >= 1.0f && samples_per_voxel <= 100.0f))) {
    throw InputError(
        fmt::format("segment samples per voxel {} is neither 0 (every pixel) nor in [1, 100]",
                    samples_per_voxel));
  }
  if (!(normals.radius > 0.0f && normals.radius <= 0.2f)) {
    throw InputError(fmt::format("normal radius {} m is outside (0, 0.2]", normals.radius));
  }
  if (normals.samples_per_axis < 3 || normals.min_neighbours < 3) {
    throw InputError("normal estimation needs at least 3 samples per axis and 3 neighbours");
  }
}

int segmentPixelStride(const OrganizedCloud& cloud, const cv::Mat& probability, float focal_px,
                       const SoftSegmentParams& params) {
  if (!(params.voxel_size > 0 && params.samples_per_voxel > 0)) return 1;
  // The far depth from the pixels on a lattice of every 4th row and column: a 16th of the image
  // settles a percentile, and the far end decides because a voxel's footprint shrinks with depth.
  constexpr int kLattice = 4;
  std::vector<float> depths;
  for (int v = 0; v < cloud.height; v += kLattice) {
    const float* prob_row = probability.ptr<float>(v);
    for (int u = 0; u < cloud.width; u += kLattice) {
      const int i = v * cloud.width + u;
      if (prob_row[u] > params.min_probability && cloud.isValid(i)) {
        depths.push_back(cloud.points[static_cast<size_t>(i)].z());
      }
    }
  }
  if (depths.empty()) return 1;
  const auto far = depths.begin() + static_cast<std::ptrdiff_t>(0.9 * (depths.size() - 1));
  std::nth_element(depths.begin(), far, depths.end());
  const float footprint_px = params.voxel_size * focal_px / *far;
  // Clamped before the cast: a depth near 0 gives footprints beyond any int.
  return static_cast<int>(std::clamp(footprint_px / params.samples_per_voxel, 1.0f,
                                     static_cast<float>(std::max(cloud.width, cloud.height))));
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

  // Pass 1, in row bands on the threads: the pixels above epsilon with depth, and their voxel keys,
  // on every stride-th row and column. Most of an image is background, below epsilon: a block of
  // 16 scanned pixels with none above it is skipped after 16 branch-free comparisons (a test and a
  // branch per pixel cost 10 instructions, 3 M per 640x480 image, a fifth of the cat's soft
  // segment).
  const int stride = segmentPixelStride(cloud, probability, focal_px, params);
  const float inv = params.voxel_size > 0 ? 1.0f / params.voxel_size : 0.0f;
  const float threshold = params.min_probability;
  struct KeptPixel {
    int pixel;
    int group;  // set by pass 2
    uint64_t key;
  };
  const int bands = std::clamp(threads, 1, std::max(1, cloud.height));
  std::vector<std::vector<KeptPixel>> band_kept(static_cast<size_t>(bands));
  auto bandRows = [&](int b) {
    return std::make_pair(b * cloud.height / bands, (b + 1) * cloud.height / bands);
  };
  for (int b = 0; b < bands; ++b) {  // reserved here: no allocation inside the parallel loop
    const auto [from, to] = bandRows(b);
    band_kept[static_cast<size_t>(b)].reserve(
        static_cast<size_t>(to - from + stride - 1) / static_cast<size_t>(stride) *
        static_cast<size_t>(cloud.width + stride - 1) / static_cast<size_t>(stride));
  }
#pragma omp parallel for num_threads(bands) schedule(static, 1)
  for (int b = 0; b < bands; ++b) {
    std::vector<KeptPixel>& kept = band_kept[static_cast<size_t>(b)];
    const auto [from, to] = bandRows(b);
    for (int v = (from + stride - 1) / stride * stride; v < to; v += stride) {
      const float* prob_row = probability.ptr<float>(v);
      auto visit = [&](int u) {
        const int i = v * cloud.width + u;
        if (!(prob_row[u] > threshold) || !cloud.isValid(i)) return;
        const uint64_t key = inv > 0 ? packVoxelCell(voxelCell(cloud.points[i], inv)) : 0;
        kept.push_back({i, -1, key});
      };
      const int block = 16 * stride;
      int u = 0;
      for (; u + block <= cloud.width; u += block) {
        int any = 0;
        for (int k = 0; k < block; k += stride) any |= prob_row[u + k] > threshold;
        if (!any) continue;
        for (int k = 0; k < block; k += stride) visit(u + k);
      }
      for (; u < cloud.width; u += stride) visit(u);
    }
  }

  // Pass 2, in image order: group the kept pixels by voxel (each pixel is its own group at voxel
  // size 0), and sum each group in that order. A voxel spans several pixels, so the key of the
  // pixel to the left or above is usually the same: remembering their groups skips most hash
  // lookups, each of which costs an integer division by the table's prime size. A remembered key
  // always maps to its group.
  constexpr uint64_t kNoKey = ~uint64_t{0};  // packVoxelCell never sets the top bit
  std::unordered_map<uint64_t, int> group_of_key;
  uint64_t left_key = kNoKey;
  int left_group = -1;
  std::vector<uint64_t> above_key(static_cast<size_t>(cloud.width), kNoKey);
  std::vector<int> above_group(static_cast<size_t>(cloud.width), -1);
  std::vector<Voxel> groups;
  for (std::vector<KeptPixel>& kept : band_kept) {
    for (KeptPixel& k : kept) {
      const int v = k.pixel / cloud.width, u = k.pixel - v * cloud.width;
      int g = static_cast<int>(groups.size());
      if (inv > 0) {
        if (k.key == left_key) {
          g = left_group;
        } else if (k.key == above_key[u]) {
          g = above_group[u];
        } else {
          g = group_of_key.try_emplace(k.key, g).first->second;
        }
        left_key = above_key[u] = k.key;
        left_group = above_group[u] = g;
      }
      if (g == static_cast<int>(groups.size())) groups.emplace_back();
      Voxel& vox = groups[static_cast<size_t>(g)];
      vox.sum += cloud.points[static_cast<size_t>(k.pixel)];
      vox.probability_sum += probability.ptr<float>(v)[u];
      ++vox.count;
      k.group = g;
    }
  }

  // Pass 3, in the bands again: the representative of a group is its pixel nearest the centroid,
  // which lies on the surface even when the centroid of a voxel straddling a depth edge does not.
  // Each band keeps its nearest per group, and the bands are merged in image order with ties to the
  // earlier, as one scan in image order would.
  std::vector<Eigen::Vector3f> centroids(groups.size());
  for (size_t g = 0; g < groups.size(); ++g) {
    centroids[g] = groups[g].sum / static_cast<float>(groups[g].count);
  }
  std::vector<std::vector<float>> band_d2(static_cast<size_t>(bands));
  std::vector<std::vector<int>> band_pixel(static_cast<size_t>(bands));
  for (int b = 0; b < bands; ++b) {
    band_d2[static_cast<size_t>(b)].assign(groups.size(), std::numeric_limits<float>::max());
    band_pixel[static_cast<size_t>(b)].assign(groups.size(), -1);
  }
#pragma omp parallel for num_threads(bands) schedule(static, 1)
  for (int b = 0; b < bands; ++b) {
    std::vector<float>& best_d2 = band_d2[static_cast<size_t>(b)];
    std::vector<int>& best = band_pixel[static_cast<size_t>(b)];
    for (const KeptPixel& k : band_kept[static_cast<size_t>(b)]) {
      const auto g = static_cast<size_t>(k.group);
      const float d2 = (cloud.points[static_cast<size_t>(k.pixel)] - centroids[g]).squaredNorm();
      if (d2 < best_d2[g]) {
        best_d2[g] = d2;
        best[g] = k.pixel;
      }
    }
  }
  std::vector<int> representative = std::move(band_pixel.front());
  for (size_t b = 1; b < band_d2.size(); ++b) {
    for (size_t g = 0; g < groups.size(); ++g) {
      if (band_d2[b][g] < band_d2.front()[g]) {
        band_d2.front()[g] = band_d2[b][g];
        representative[g] = band_pixel[b][g];
      }
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
    segment.points.push_back(centroids[g]);
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
  if (boundary_map.cols != width || boundary_map.rows != height) {
    throw InputError(fmt::format("boundary map is {}x{} but the image is {}x{}", boundary_map.cols,
                                 boundary_map.rows, width, height));
  }
  const BoundaryRegions regions(boundary_map);  // checks the type
  segment.region.resize(segment.size());
  for (size_t i = 0; i < segment.size(); ++i) {
    const int region = regions.at(segment.pixel[i] % width, segment.pixel[i] / width);
    segment.region[i] = region > 0 ? region : -1;  // region 0 is the boundary itself
  }
}

}  // namespace stocs
