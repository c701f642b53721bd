#include "stocs/ppf.h"

#include <stdexcept>

namespace stocs {
namespace {

/// Own bin and nearer-edge neighbour of x in [0, bins); `second` is -1 when it falls outside.
struct BinPair {
  int first, second;
};

BinPair binPair(float x, float step, int bins) {
  const float s = x / step;
  int q = static_cast<int>(std::floor(s));
  q = std::clamp(q, 0,
                 bins - 1);  // the closed end of an angle range (exactly pi) joins the last bin
  const int other = (s - q >= 0.5f) ? q + 1 : q - 1;
  return {q, (other >= 0 && other < bins) ? other : -1};
}

}  // namespace

PpfQuantizer::PpfQuantizer(float distance_step, float angle_step, float max_distance)
    : distance_step_(distance_step), angle_step_(angle_step) {
  if (!(distance_step > 0) || !(angle_step > 0) || !(max_distance > 0)) {
    throw std::invalid_argument("PPF steps and range must be positive");
  }
  distance_bins_ = static_cast<int>(std::floor(max_distance / distance_step)) + 2;
  angle_bins_ = static_cast<int>(std::ceil(static_cast<float>(M_PI) / angle_step - 1e-4f));
}

bool PpfQuantizer::key(const PpfFeature& f, uint32_t& out) const {
  const int d = static_cast<int>(std::floor(f.distance / distance_step_));
  if (d < 0 || d >= distance_bins_) return false;
  auto a = [&](float x) {
    return std::clamp(static_cast<int>(std::floor(x / angle_step_)), 0, angle_bins_ - 1);
  };
  out = pack(d, a(f.angle_n1_d), a(f.angle_n2_d), a(f.angle_n1_n2));
  return true;
}

int PpfQuantizer::nearestKeys(const PpfFeature& f, Keys& out) const {
  if (!(f.distance >= 0) || f.distance / distance_step_ >= distance_bins_) return 0;
  const BinPair dims[4] = {binPair(f.distance, distance_step_, distance_bins_),
                           binPair(f.angle_n1_d, angle_step_, angle_bins_),
                           binPair(f.angle_n2_d, angle_step_, angle_bins_),
                           binPair(f.angle_n1_n2, angle_step_, angle_bins_)};
  int n = 0;
  for (int mask = 0; mask < kNearest; ++mask) {
    int idx[4];
    bool in_range = true;
    for (int k = 0; k < 4; ++k) {
      idx[k] = (mask >> k) & 1 ? dims[k].second : dims[k].first;
      in_range = in_range && idx[k] >= 0;
    }
    if (in_range) out[n++] = pack(idx[0], idx[1], idx[2], idx[3]);
  }
  return n;
}

}  // namespace stocs
