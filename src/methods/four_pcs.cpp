// Parameters of both PCL 4PCS baselines (pcl/registration/ia_fpcs.h and PCL's own tests):
//   delta            max(segment voxel size, model sampling radius), absolute: "the point accuracy
//                    to ensure finding neighbors between source <-> target"; PCL's normalised
//                    default (1 x the target's mean spacing) gives about the same, not reproducibly
//   approx. overlap  PCL's default 0.5, scaled down by the ratio of the model's diameter to the
//                    target's extent when the segment is larger than the object (clutter, or a
//                    bin of identical instances). PCL draws bases up to 2 x overlap x the target's
//                    bounding-box diagonal wide (ia_fpcs.hpp); the Super4PCS/OpenGR authors
//                    advise dividing the overlap by how much larger the bounding box is than the
//                    object (OpenGR issue #74), since a base wider than the object has no
//                    congruent set on it. With 0.5 on a packed bin of identical instances every
//                    base spans several of them and finds no candidate.
//   number of samples 100 model samples, as PCL's FPCS test (test_fpcs_ia_data.h); drawn here
//   max. iterations  the StoCS base budget (one PCL iteration = one base with its congruent sets)
//   max. time        the StoCS time budget rounded up to whole seconds (PCL counts whole seconds
//                    and checks between bases only)
//   score threshold  0: no early stop, every base of the budget is tried
//   normals          given (segment and model normals); max. normal difference 90 deg (default)
#include "four_pcs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "stocs/util/random.h"

namespace stocs {
namespace {

constexpr size_t kSourceSamples = 100;

/// Every index of `n` when `count` is 0 or not below n, else `count` distinct indices drawn
/// uniformly with `seed` (partial Fisher-Yates), in increasing order.
std::vector<size_t> sampleIndices(size_t n, size_t count, uint64_t seed) {
  std::vector<size_t> indices(n);
  std::iota(indices.begin(), indices.end(), size_t{0});
  if (count == 0 || count >= n) return indices;
  Rng rng(seed);
  for (size_t i = 0; i < count; ++i) {
    std::swap(indices[i], indices[i + uniformIndex(rng, static_cast<uint32_t>(n - i))]);
  }
  indices.resize(count);
  std::sort(indices.begin(), indices.end());
  return indices;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr toPoints(const std::vector<Eigen::Vector3f>& points,
                                             const std::vector<size_t>& indices) {
  auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  cloud->reserve(indices.size());
  for (size_t i : indices)
    cloud->push_back(pcl::PointXYZ(points[i].x(), points[i].y(), points[i].z()));
  return cloud;
}

pcl::PointCloud<pcl::Normal>::Ptr toNormals(const std::vector<Eigen::Vector3f>& normals,
                                            const std::vector<size_t>& indices) {
  auto cloud = pcl::make_shared<pcl::PointCloud<pcl::Normal>>();
  cloud->reserve(indices.size());
  for (size_t i : indices)
    cloud->push_back(pcl::Normal(normals[i].x(), normals[i].y(), normals[i].z()));
  return cloud;
}

/// PCL's overlap for a target of bounding-box diagonal `target_extent` and a model of diameter
/// `model_diameter`: the default 0.5, or less, so that bases are at most the object's diameter
/// wide.
float approxOverlap(float model_diameter, float target_extent) {
  constexpr float kPclDefault = 0.5f;
  if (!(target_extent > model_diameter) || !(model_diameter > 0)) return kPclDefault;
  return kPclDefault * model_diameter / target_extent;
}

float boundingBoxDiagonal(const std::vector<Eigen::Vector3f>& points) {
  Eigen::AlignedBox3f box;
  for (const Eigen::Vector3f& p : points) box.extend(p);
  return box.isEmpty() ? 0.0f : box.diagonal().norm();
}

}  // namespace

unsigned fourPcsSeed(uint64_t seed) {
  return static_cast<unsigned>(streamSeed(seed, 0));
}

std::optional<BaselineHypothesis> alignFourPcs(FourPcs& aligner, const SoftSegment& segment,
                                               const ObjectInput& input) {
  const ObjectModel& model = input.model->model;
  const StocsParams& budget = input.params->stocs;
  // Every pair of source points is compared per base and every candidate validated on all of them,
  // so the cost per base grows with the square of the source's size. Drawn here rather than by
  // setNumberOfSamples(), which draws with the clock-seeded std::rand in initCompute().
  const std::vector<size_t> source =
      sampleIndices(model.size(), kSourceSamples, streamSeed(budget.seed, 1));
  aligner.setInputSource(toPoints(model.points, source));
  aligner.setSourceNormals(toNormals(model.normals, source));
  const std::vector<size_t> target = sampleIndices(segment.size(), 0, 0);
  aligner.setInputTarget(toPoints(segment.points, target));
  aligner.setTargetNormals(toNormals(segment.normals, target));
  aligner.setDelta(std::max(input.params->segment.voxel_size, model.sampling_radius), false);
  aligner.setApproxOverlap(approxOverlap(model.diameter, boundingBoxDiagonal(segment.points)));
  aligner.setMaximumIterations(budget.bases);
  if (budget.time_budget > 0) {
    aligner.setMaxComputationTime(static_cast<int>(std::ceil(budget.time_budget)));  // whole s
  }
  aligner.setScoreThreshold(0.0f);
  pcl::PointCloud<pcl::PointXYZ> aligned;
  aligner.align(aligned);
  const float fitness = aligner.getFitnessScore();  // lower is better, max() without a candidate
  if (!(fitness < std::numeric_limits<float>::max())) return std::nullopt;
  BaselineHypothesis h;
  h.pose.matrix() = aligner.getFinalTransformation();
  h.score = 1.0 - fitness;
  return h;
}

}  // namespace stocs
