#include "stocs/lcp_scorer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "stocs/error.h"

namespace stocs {
namespace {

struct Span {
  const uint32_t* data;
  size_t count;
  size_t size() const { return count; }
  uint32_t operator[](size_t k) const { return data[k]; }
};

}  // namespace

void LcpParams::validate() const {
  if (!(distance > 0.0f && distance <= 0.1f)) {
    throw InputError(fmt::format("LCP distance delta_s {} m is outside (0, 0.1]", distance));
  }
  if (!(normal_angle_deg > 0.0f && normal_angle_deg <= 180.0f)) {
    throw InputError(
        fmt::format("LCP normal angle delta_n {} deg is outside (0, 180]", normal_angle_deg));
  }
  if (!(coarse_fraction >= 0.0f && coarse_fraction < 1.0f) ||
      !(coarse_ratio > 0.0f && coarse_ratio <= 1.0f)) {
    throw InputError(
        fmt::format("coarse verification fraction {} / ratio {} are outside [0, 1) / (0, 1]",
                    coarse_fraction, coarse_ratio));
  }
}

LcpScorer::LcpScorer(const SoftSegment& segment, const LcpParams& params)
    : segment_(segment),
      params_((params.validate(), params)),  // before the grid uses delta_s
      grid_(segment.points, params.distance),
      cos_normal_(std::cos(params.normal_angle_deg * static_cast<float>(M_PI) / 180.0f)),
      sin_normal_(params.normal_angle_deg >= 90.0f
                      ? 1.0f
                      : std::sin(params.normal_angle_deg * static_cast<float>(M_PI) / 180.0f)) {
  for (float p : segment.probability) max_probability_ = std::max(max_probability_, p);
  // One grid per instance region, so that region-restricted searches need no per-point test.
  std::unordered_map<int, std::vector<uint32_t>> members;
  for (size_t i = 0; i < segment.region.size(); ++i) {
    if (segment.region[i] >= 0) members[segment.region[i]].push_back(static_cast<uint32_t>(i));
  }
  for (const auto& [region, subset] : members) {
    region_grids_.emplace(region, NeighbourhoodGrid(segment.points, subset, params.distance));
  }
  empty_ = NeighbourhoodGrid(segment.points, std::vector<uint32_t>{}, params.distance);
}

const NeighbourhoodGrid& LcpScorer::gridOf(int region) const {
  if (region < 0 || segment_.region.empty()) return grid_;
  const auto it = region_grids_.find(region);
  return it == region_grids_.end() ? empty_ : it->second;
}

float LcpScorer::score(const ObjectModel& model, const Eigen::Isometry3f& pose, int region,
                       float must_reach) const {
  const Eigen::Matrix3f r = pose.linear();
  const Eigen::Vector3f t = pose.translation();
  // A model point can only match when its normal n satisfies n.v <= sin(delta_n) for the viewing
  // ray v: scene normals face the camera (N.v <= 0) and must be within delta_n of n. Counting the
  // points that pass this cheap test first gives an exact upper bound for the early stop. The test
  // runs in the model frame, where the camera-frame point R m + t is m + R^T t up to the rotation:
  // (R n).(R m + t) = n.(m + R^T t) and |R m + t| = |m + R^T t|, so no point is transformed.
  const Eigen::Vector3f camera_offset = r.transpose() * t;
  const float sin2 = sin_normal_ * sin_normal_;
  thread_local std::vector<uint32_t> facing_storage;
  facing_storage.resize(model.size());
  size_t facing_count = 0;
  for (size_t i = 0; i < model.size(); ++i) {  // branch-free: about half the points pass
    const Eigen::Vector3f q = model.points[i] + camera_offset;
    const float nq = model.normals[i].dot(q);
    facing_storage[facing_count] = static_cast<uint32_t>(i);
    facing_count += nq <= 0 || nq * nq <= sin2 * q.squaredNorm();
  }
  const Span facing{facing_storage.data(), facing_count};
  const NeighbourhoodGrid& grid = gridOf(region);
  // Coarse-to-fine: checks after coarse_fraction of the facing points and again after every
  // doubling of the points seen (1/8, 1/4, 1/2 by default).
  size_t coarse_check = static_cast<size_t>(std::ceil(params_.coarse_fraction * facing.size()));
  float total = 0;
  for (size_t visited = 0; visited < facing.size(); ++visited) {
    // Check the bound every 16 candidates: cheap, and exact because it never discards a pose that
    // could reach must_reach.
    const size_t remaining = facing.size() - visited;
    if ((visited & 15) == 0 && total + remaining * max_probability_ < must_reach) return -1.0f;
    if (visited == coarse_check && coarse_check > 0) {
      if (total * facing.size() < params_.coarse_ratio * must_reach * visited) return -1.0f;
      coarse_check *= 2;
    }
    const uint32_t i = facing[visited];
    const int s = grid.closest(r * model.points[i] + t);
    if (s < 0) continue;
    if ((r * model.normals[i]).dot(segment_.normals[s]) > cos_normal_)
      total += segment_.probability[s];
  }
  return total;
}

LcpDetail LcpScorer::detail(const ObjectModel& model, const Eigen::Isometry3f& pose,
                            int region) const {
  LcpDetail d;
  double confidence = 0;
  for (size_t i = 0; i < model.size(); ++i) {
    const Eigen::Vector3f p = pose * model.points[i];
    const Eigen::Vector3f n = pose.linear() * model.normals[i];
    d.facing += n.dot(p) < 0;
    const int s = closest(p, region);
    if (s < 0 || !(n.dot(segment_.normals[s]) > cos_normal_)) continue;
    d.score += segment_.probability[s];
    confidence += segment_.confidence[s];
    ++d.matched;
  }
  d.mean_confidence = d.matched ? static_cast<float>(confidence / d.matched) : 0.0f;
  return d;
}

}  // namespace stocs
