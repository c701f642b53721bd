#include "stocs/estimation/stages/lcp_scorer.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "stocs/util/error.h"

namespace stocs {

const ParamSet<LcpParams>& LcpParams::schema() {
  static const ParamSet<LcpParams> schema =
      ParamSet<LcpParams>()
          .add(&LcpParams::distance, "distance", "m", ParamRange::aboveUpTo(0, 0.1),
               "delta_s: a model point is matched by a segment point this close")
          .flag("--delta-s")
          .add(&LcpParams::normal_angle_deg, "normal_angle_deg", "deg",
               ParamRange::aboveUpTo(0, 180), "delta_n: matched normals agree within this angle")
          .flag("--delta-n")
          .add(&LcpParams::coarse_fraction, "coarse_fraction", "", ParamRange::fromBelow(0, 1),
               "share of the model scored first, then checked again after each share; 0: no coarse "
               "checks")
          .flag("--coarse-fraction")
          .add(&LcpParams::coarse_ratio, "coarse_ratio", "", ParamRange::aboveUpTo(0, 1),
               "a hypothesis whose first coarse score is below this share of the score to beat is "
               "dropped")
          .flag("--coarse-ratio");
  return schema;
}

void LcpParams::validate() const {
  schema().validate(*this);
}

LcpScorer::LcpScorer(const SoftSegment& segment, const LcpParams& params)
    : segment_(segment),
      params_((params.validate(), params)),  // before the grid uses delta_s
      grids_(segment.points, segment.region, params.distance),
      cos_normal_(std::cos(params.normal_angle_deg * static_cast<float>(M_PI) / 180.0f)),
      sin_normal_(params.normal_angle_deg >= 90.0f
                      ? 1.0f
                      : std::sin(params.normal_angle_deg * static_cast<float>(M_PI) / 180.0f)) {
  for (float p : segment.probability) max_probability_ = std::max(max_probability_, p);
}

uint32_t LcpScorer::headSize(size_t model_points) const {
  // Rounded up to whole chunks, so that every later check falls on a chunk boundary.
  const auto n = static_cast<uint32_t>(model_points);
  if (params_.coarse_fraction <= 0) return n;
  const auto head = static_cast<uint32_t>(std::ceil(params_.coarse_fraction * n));
  return std::min(n, (head + kChunk - 1) / kChunk * kChunk);
}

bool LcpScorer::advance(const ObjectModel& model, const Eigen::Isometry3f& pose, int region,
                        PartialScore& partial, uint32_t end, float must_reach) const {
  const Eigen::Matrix3f r = pose.linear();
  const Eigen::Vector3f t = pose.translation();
  // A model point can only match when its normal n satisfies n.v <= sin(delta_n) for the viewing
  // ray v: scene normals face the camera (N.v <= 0) and must be within delta_n of n. The test runs
  // in the model frame, where the camera-frame point R m + t is m + R^T t up to the rotation:
  // (R n).(R m + t) = n.(m + R^T t) and |R m + t| = |m + R^T t|, so no point is transformed. It
  // runs lazily, a chunk at a time, because most hypotheses stop after a few chunks.
  const Eigen::Vector3f camera_offset = r.transpose() * t;
  const float sin2 = sin_normal_ * sin_normal_;
  const NeighbourhoodGrid& grid = grids_.of(region);
  const auto n = static_cast<uint32_t>(model.size());
  // Coarse-to-fine: checks after every coarse_fraction of the model points (1/8, 2/8, ... by
  // default). The points seen are a sample drawn without replacement from the model's, so the
  // relative error of the extrapolated objective shrinks as sqrt((1 - f) / f) at fraction f seen,
  // and so does the margin allowed below must_reach: 1 - coarse_ratio at the first check (0.5,
  // 0.33, 0.25, 0.19, ..., 0.07 by default).
  const uint32_t first_check = params_.coarse_fraction > 0 ? headSize(n) : 0;
  std::array<uint32_t, kChunk> facing;
  while (partial.seen < end) {
    // Exact: even if every remaining point matched at the highest probability, must_reach is out
    // of reach.
    if (partial.total + (n - partial.seen) * max_probability_ < must_reach) return false;
    if (first_check > 0 && partial.seen > 0 && partial.seen % first_check == 0) {
      const float margin = (1.0f - params_.coarse_ratio) *
                           std::sqrt(static_cast<float>(n - partial.seen) / partial.seen /
                                     (static_cast<float>(n - first_check) / first_check));
      if (partial.total * n < (1.0f - margin) * must_reach * partial.seen) return false;
    }
    const uint32_t chunk_end = std::min(end, partial.seen + kChunk);
    uint32_t count = 0;
    for (uint32_t i = partial.seen; i < chunk_end; ++i) {  // branch-free: about half pass
      const Eigen::Vector3f q = model.points[i] + camera_offset;
      const float nq = model.normals[i].dot(q);
      facing[count] = i;
      count += nq <= 0 || nq * nq <= sin2 * q.squaredNorm();
    }
    for (uint32_t k = 0; k < count; ++k) {
      const uint32_t i = facing[k];
      const int s = grid.closest(r * model.points[i] + t);
      if (s < 0) continue;
      if (normalsAgree(r * model.normals[i], segment_.normals[s]))
        partial.total += segment_.probability[s];
    }
    partial.seen = chunk_end;
  }
  return true;
}

float LcpScorer::score(const ObjectModel& model, const Eigen::Isometry3f& pose, int region,
                       float must_reach) const {
  PartialScore partial;
  return finishScore(model, pose, region, partial, must_reach);
}

void LcpScorer::extendHead(const ObjectModel& model, const Eigen::Isometry3f& pose, int region,
                           PartialScore& partial, float share) const {
  const uint32_t head = headSize(model.size());
  const auto chunks = static_cast<uint32_t>(std::ceil(share * static_cast<float>(head) / kChunk));
  advance(model, pose, region, partial, std::min(head, chunks * kChunk),
          -std::numeric_limits<float>::infinity());
}

float LcpScorer::finishScore(const ObjectModel& model, const Eigen::Isometry3f& pose, int region,
                             PartialScore partial, float must_reach) const {
  const auto n = static_cast<uint32_t>(model.size());
  return advance(model, pose, region, partial, n, must_reach) ? partial.total : -1.0f;
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
    if (s < 0 || !normalsAgree(n, segment_.normals[s])) continue;
    d.score += segment_.probability[s];
    confidence += segment_.confidence[s];
    ++d.matched;
  }
  d.mean_confidence = d.matched ? static_cast<float>(confidence / d.matched) : 0.0f;
  return d;
}

}  // namespace stocs
