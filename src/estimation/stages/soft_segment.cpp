#include "stocs/estimation/stages/soft_segment.h"

#include <fmt/format.h>

#include <omp.h>
#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <opencv2/core.hpp>

#include "stocs/estimation/stages/boundary_regions.h"
#include "stocs/geometry/voxel_key.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

struct Voxel {
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  double probability_sum = 0;
  int count = 0;
};

/// Voxel key to group, by open addressing with linear probing in a power-of-two table kept at
/// most half full, rather than std::unordered_map, which allocates a node for every voxel and
/// divides by a prime on every lookup: costly where voxels hold a few pixels each.
class GroupOfKey {
 public:
  /// The group of `key`, or `next`, which the key then maps to, when the key is new.
  int findOrAdd(uint64_t key, int next) {
    if (2 * (size_ + 1) > slots_.size()) grow();
    for (size_t i = slotOf(key);; i = (i + 1) & mask_) {
      Slot& slot = slots_[i];
      if (slot.group < 0) {
        slot = {key, next};
        ++size_;
        return next;
      }
      if (slot.key == key) return slot.group;
    }
  }

  /// Forgets every key, keeping the table's size.
  void clear() {
    std::fill(slots_.begin(), slots_.end(), Slot{0, -1});
    size_ = 0;
  }

 private:
  struct Slot {
    uint64_t key;
    int group;  // -1: empty
  };
  // Fibonacci hashing: the top bits of the key times 2^64 over the golden ratio.
  size_t slotOf(uint64_t key) const {
    return static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
  }
  void grow() {
    std::vector<Slot> old = std::move(slots_);
    const size_t capacity = std::max<size_t>(256, 2 * old.size());
    slots_.assign(capacity, Slot{0, -1});
    mask_ = capacity - 1;
    shift_ = 64 - __builtin_ctzll(capacity);
    size_ = 0;
    for (const Slot& slot : old) {
      if (slot.group >= 0) findOrAdd(slot.key, slot.group);
    }
  }

  std::vector<Slot> slots_;
  size_t size_ = 0, mask_ = 0;
  int shift_ = 64;
};

}  // namespace

const ParamSet<SoftSegmentParams>& SoftSegmentParams::schema() {
  static const ParamSet<SoftSegmentParams> schema =
      ParamSet<SoftSegmentParams>()
          .add(&SoftSegmentParams::min_probability, "min_probability", "",
               ParamRange::fromBelow(0, 1),
               "epsilon: pixels with a class probability above it join the soft segment")
          .flag("--epsilon")
          .add(&SoftSegmentParams::voxel_size, "voxel_size", "m", ParamRange::closed(0, 0.1),
               "segment points are centroids of voxels of this size; 0 keeps every pixel")
          .flag("--voxel")
          .add(&SoftSegmentParams::samples_per_voxel, "samples_per_voxel", "",
               ParamRange::closed(1, 100).orAlso(0),
               "pixel samples across a voxel at the segment's far depth: sets the scan stride; 0: "
               "every pixel")
          .flag("--samples-per-voxel")
          .nest(&SoftSegmentParams::normals, "normals", OrganizedNormalParams::schema());
  return schema;
}

void SoftSegmentParams::validate() const {
  schema().validate(*this);
}

namespace {

/// The pixels a segment scans: `roi` clipped to the image, or the whole image.
cv::Rect scanArea(const OrganizedCloud& cloud, const std::optional<cv::Rect>& roi) {
  const cv::Rect image(0, 0, cloud.width, cloud.height);
  return roi ? (*roi & image) : image;
}

}  // namespace

int segmentPixelStride(const OrganizedCloud& cloud, const cv::Mat& probability, float focal_px,
                       const SoftSegmentParams& params, const std::optional<cv::Rect>& roi) {
  if (!(params.voxel_size > 0 && params.samples_per_voxel > 0)) return 1;
  // The far depth from the pixels on a lattice of every 4th row and column: a 16th of the image
  // settles a percentile, and the far end decides because a voxel's footprint shrinks with depth.
  constexpr int kLattice = 4;
  const cv::Rect area = scanArea(cloud, roi);
  std::vector<float> depths;
  for (int v = area.y; v < area.y + area.height; v += kLattice) {
    const float* prob_row = probability.ptr<float>(v);
    for (int u = area.x; u < area.x + area.width; u += kLattice) {
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

namespace {

/// Rows of a chunk: the image is cut into chunks of kChunkRows rows, handed to the threads as they
/// come free (the object's pixels crowd into a few rows, and halves of the image would leave one
/// thread idle for most of the scan). The chunks are the same for every thread count, and so is the
/// result.
constexpr int kChunkRows = 16;
constexpr uint64_t kNoKey = ~uint64_t{0};  // packVoxelCell never sets the top bit

/// A scanned pixel above epsilon with depth.
struct KeptPixel {
  int pixel;
  int group;  // in its chunk
};

/// What pass 1 finds in one chunk, and pass 2's numbering of its groups.
struct Chunk {
  std::vector<KeptPixel> kept;  // in image order
  std::vector<Voxel> groups;    // in order of first pixel
  std::vector<uint64_t> keys;   // of the groups
  std::vector<int> merged;      // group of the segment, per group of the chunk
};

/// What a thread remembers from chunk to chunk, allocated before the threads start: an exception
/// must not leave an OpenMP region, and the chunks' own growth is caught in scanChunks.
struct Scanner {
  explicit Scanner(int width)
      : above_key(static_cast<size_t>(width), kNoKey),
        above_group(static_cast<size_t>(width), -1) {}

  GroupOfKey group_of_key;
  std::vector<uint64_t> above_key;
  std::vector<int> above_group;
  bool dirty = false;  // the previous chunk kept pixels (most chunks of an image keep none)
};

/// The last key seen on a chunk's current row, and its group.
struct LeftKey {
  uint64_t key = kNoKey;
  int group = -1;
};

/// What the passes read of the image.
struct SegmentInput {
  const OrganizedCloud& cloud;
  const cv::Mat& probability;
  cv::Rect area;    // the pixels scanned (scanArea)
  int stride;       // scan every stride-th row and column
  float inv_voxel;  // 1 / voxel size; 0: every pixel is its own group
  float threshold;  // epsilon
};

/// Throws InputError unless the probability image is a CV_32FC1 image of the cloud's size and the
/// focal length is positive.
void checkSegmentInputs(const OrganizedCloud& cloud, const cv::Mat& probability, float focal_px) {
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
}

/// Pass 1 on row v of a chunk: its kept pixels, each added to its group.
void scanRow(const SegmentInput& in, int v, Chunk& chunk, Scanner& scanner, LeftKey& left) {
  const OrganizedCloud& cloud = in.cloud;
  const int stride = in.stride;
  const float* prob_row = in.probability.ptr<float>(v);
  auto visit = [&](int u) {
    const int i = v * cloud.width + u;
    if (!(prob_row[u] > in.threshold) || !cloud.isValid(i)) return;
    const Eigen::Vector3f& p = cloud.points[static_cast<size_t>(i)];
    int g = static_cast<int>(chunk.groups.size());
    if (in.inv_voxel > 0) {
      const uint64_t key = packVoxelCell(voxelCell(p, in.inv_voxel));
      if (key == left.key) {
        g = left.group;
      } else if (key == scanner.above_key[u]) {
        g = scanner.above_group[u];
      } else {
        g = scanner.group_of_key.findOrAdd(key, g);
      }
      left.key = scanner.above_key[u] = key;
      left.group = scanner.above_group[u] = g;
      if (g == static_cast<int>(chunk.groups.size())) chunk.keys.push_back(key);
    }
    if (g == static_cast<int>(chunk.groups.size())) chunk.groups.emplace_back();
    Voxel& vox = chunk.groups[static_cast<size_t>(g)];
    vox.sum += p;
    vox.probability_sum += prob_row[u];
    ++vox.count;
    chunk.kept.push_back({i, g});
  };
  const int block = 16 * stride;
  const int end = in.area.x + in.area.width;
  int u = (in.area.x + stride - 1) / stride * stride;  // the columns of the whole image's lattice
  for (; u + block <= end; u += block) {
    int any = 0;
    for (int k = 0; k < block; k += stride) any |= prob_row[u + k] > in.threshold;
    if (!any) continue;
    for (int k = 0; k < block; k += stride) visit(u + k);
  }
  for (; u < end; u += stride) visit(u);
}

/// Pass 1 on chunk c, with the memory of the thread that takes it.
///
/// The pixels above epsilon with depth, on every stride-th row and column, grouped by voxel (each
/// pixel is its own group at voxel size 0) in image order, each group summed in that order. Most
/// of an image is background, below epsilon: a block of 16 scanned pixels with none above it is
/// skipped after 16 branch-free comparisons, cheaper than a test and a branch per pixel. A voxel
/// spans several pixels, so the key of the pixel to the left or above is usually the same:
/// remembering their groups skips most hash lookups. A remembered key always maps to its group.
void scanChunk(const SegmentInput& in, std::ptrdiff_t c, Chunk& chunk, Scanner& scanner) {
  if (scanner.dirty) {
    scanner.group_of_key.clear();
    std::fill(scanner.above_key.begin(), scanner.above_key.end(), kNoKey);
  }
  LeftKey left;
  const int from = in.area.y + static_cast<int>(c) * kChunkRows;
  const int to = std::min(in.area.y + in.area.height, from + kChunkRows);
  for (int v = (from + in.stride - 1) / in.stride * in.stride; v < to; v += in.stride) {
    scanRow(in, v, chunk, scanner, left);
  }
  scanner.dirty = !chunk.kept.empty();
}

/// Pass 1 on every chunk, on `team` threads; rethrows the first exception of a thread.
void scanChunks(const SegmentInput& in, std::vector<Chunk>& chunks, int team) {
  std::vector<Scanner> scanners(static_cast<size_t>(team), Scanner(in.cloud.width));
  const auto chunk_count = static_cast<std::ptrdiff_t>(chunks.size());
  std::exception_ptr error;
#pragma omp parallel for num_threads(team) schedule(dynamic, 1)
  for (std::ptrdiff_t c = 0; c < chunk_count; ++c) {
    try {
      scanChunk(in, c, chunks[static_cast<size_t>(c)],
                scanners[static_cast<size_t>(omp_get_thread_num())]);
    } catch (...) {
#pragma omp critical(stocs_soft_segment_error)
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
}

/// Pass 2, the chunks in image order: a voxel across chunks becomes one group of the segment,
/// numbered in order of first pixel (each chunk's `merged`). Its sums go on from the earlier
/// chunks' pixel by pixel, so that every sum is taken in image order whatever the chunks (a
/// chunk's later voxels start in it, and voxels from earlier chunks end within a few rows of its
/// top).
std::vector<Voxel> mergeChunks(const SegmentInput& in, std::vector<Chunk>& chunks) {
  size_t chunk_groups = 0;
  for (const Chunk& chunk : chunks) chunk_groups += chunk.groups.size();
  std::vector<Voxel> groups;
  groups.reserve(chunk_groups);
  GroupOfKey group_of_key;
  std::vector<char> continued;
  for (Chunk& chunk : chunks) {
    chunk.merged.resize(chunk.groups.size());
    continued.assign(chunk.groups.size(), 0);
    int pending = 0;  // pixels of groups begun in earlier chunks
    for (size_t l = 0; l < chunk.groups.size(); ++l) {
      const int next = static_cast<int>(groups.size());
      const int g = in.inv_voxel > 0 ? group_of_key.findOrAdd(chunk.keys[l], next) : next;
      if (g == next) {
        groups.push_back(chunk.groups[l]);
      } else {
        continued[l] = 1;
        pending += chunk.groups[l].count;
      }
      chunk.merged[l] = g;
    }
    for (auto k = chunk.kept.begin(); pending > 0; ++k) {
      if (!continued[static_cast<size_t>(k->group)]) continue;
      Voxel& vox = groups[static_cast<size_t>(chunk.merged[static_cast<size_t>(k->group)])];
      vox.sum += in.cloud.points[static_cast<size_t>(k->pixel)];
      vox.probability_sum +=
          in.probability.ptr<float>(k->pixel / in.cloud.width)[k->pixel % in.cloud.width];
      ++vox.count;
      --pending;
    }
  }
  return groups;
}

/// The centroid of each group.
std::vector<Eigen::Vector3f> centroidsOf(const std::vector<Voxel>& groups) {
  std::vector<Eigen::Vector3f> centroids(groups.size());
  for (size_t g = 0; g < groups.size(); ++g) {
    centroids[g] = groups[g].sum / static_cast<float>(groups[g].count);
  }
  return centroids;
}

/// Each thread's pixel nearest each group's centroid (-1 where it saw none), and its squared
/// distance.
struct TeamNearest {
  std::vector<std::vector<float>> d2;
  std::vector<std::vector<int>> pixel;
};

/// The threads' nearest pixels merged with ties to the lower pixel index, as one scan in image
/// order would.
std::vector<int> mergeNearest(TeamNearest& team) {
  std::vector<int> representative = std::move(team.pixel.front());
  std::vector<float>& nearest = team.d2.front();
  for (size_t t = 1; t < team.d2.size(); ++t) {
    for (size_t g = 0; g < representative.size(); ++g) {
      const int pixel = team.pixel[t][g];
      if (pixel < 0) continue;
      if (team.d2[t][g] < nearest[g] ||
          (team.d2[t][g] == nearest[g] && (representative[g] < 0 || pixel < representative[g]))) {
        nearest[g] = team.d2[t][g];
        representative[g] = pixel;
      }
    }
  }
  return representative;
}

/// Pass 3, per chunk again: the representative of a group is its pixel nearest the centroid,
/// which lies on the surface even when the centroid of a voxel straddling a depth edge does not.
/// Each thread keeps its nearest per group, the first in image order of equals (a thread takes its
/// chunks in increasing order), and mergeNearest merges the threads'.
std::vector<int> representatives(const OrganizedCloud& cloud, const std::vector<Chunk>& chunks,
                                 const std::vector<Eigen::Vector3f>& centroids, int team_size) {
  const auto team = static_cast<size_t>(team_size);
  TeamNearest nearest{
      std::vector<std::vector<float>>(
          team, std::vector<float>(centroids.size(), std::numeric_limits<float>::max())),
      std::vector<std::vector<int>>(team, std::vector<int>(centroids.size(), -1))};
  const auto chunk_count = static_cast<std::ptrdiff_t>(chunks.size());
#pragma omp parallel num_threads(team_size)
  {
    const auto t = static_cast<size_t>(omp_get_thread_num());
    std::vector<float>& best_d2 = nearest.d2[t];
    std::vector<int>& best = nearest.pixel[t];
#pragma omp for schedule(dynamic, 1)
    for (std::ptrdiff_t c = 0; c < chunk_count; ++c) {
      const Chunk& chunk = chunks[static_cast<size_t>(c)];
      for (const KeptPixel& k : chunk.kept) {
        const auto g = static_cast<size_t>(chunk.merged[static_cast<size_t>(k.group)]);
        const float d2 = (cloud.points[static_cast<size_t>(k.pixel)] - centroids[g]).squaredNorm();
        if (d2 < best_d2[g]) {
          best_d2[g] = d2;
          best[g] = k.pixel;
        }
      }
    }
  }
  return mergeNearest(nearest);
}

/// The normal at each group's representative pixel, on `threads` threads.
std::vector<Eigen::Vector3f> normalsAt(const OrganizedCloud& cloud,
                                       const std::vector<int>& representative, float focal_px,
                                       const OrganizedNormalParams& params, int threads) {
  std::vector<Eigen::Vector3f> normals(representative.size());
  const auto group_count = static_cast<std::ptrdiff_t>(representative.size());
#pragma omp parallel for num_threads(std::max(1, threads)) schedule(static)
  for (std::ptrdiff_t g = 0; g < group_count; ++g) {
    normals[g] = organizedNormal(cloud, representative[g], focal_px, params);
  }
  return normals;
}

/// The segment of the groups with a normal, in group order (order of first pixel: deterministic).
SoftSegment assembleSegment(const std::vector<Voxel>& groups,
                            const std::vector<Eigen::Vector3f>& centroids,
                            const std::vector<Eigen::Vector3f>& normals,
                            const std::vector<int>& representative) {
  SoftSegment segment;
  double total = 0;
  for (size_t g = 0; g < groups.size(); ++g) {
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

}  // namespace

SoftSegment buildSoftSegment(const OrganizedCloud& cloud, const cv::Mat& probability,
                             float focal_px, const SoftSegmentParams& params, int threads,
                             const std::optional<cv::Rect>& roi) {
  params.validate();
  checkSegmentInputs(cloud, probability, focal_px);
  const SegmentInput in{cloud,
                        probability,
                        scanArea(cloud, roi),
                        segmentPixelStride(cloud, probability, focal_px, params, roi),
                        params.voxel_size > 0 ? 1.0f / params.voxel_size : 0.0f,
                        params.min_probability};
  std::vector<Chunk> chunks(static_cast<size_t>((in.area.height + kChunkRows - 1) / kChunkRows));
  const int team = std::clamp(threads, 1, static_cast<int>(std::max<size_t>(1, chunks.size())));
  scanChunks(in, chunks, team);
  const std::vector<Voxel> groups = mergeChunks(in, chunks);
  const std::vector<Eigen::Vector3f> centroids = centroidsOf(groups);
  const std::vector<int> representative = representatives(cloud, chunks, centroids, team);
  return assembleSegment(groups, centroids,
                         normalsAt(cloud, representative, focal_px, params.normals, threads),
                         representative);
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
