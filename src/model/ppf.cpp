#include "stocs/model/ppf.h"

#include <stdexcept>

#include "stocs/util/fast_floor.h"

namespace stocs {
namespace {

/// Own bin and nearer-edge neighbour of x in [0, bins); `second` is -1 when it falls outside.
struct BinPair {
  int first, second;
};

BinPair binPair(float x, float step, int bins) {
  const float s = x / step;
  int q = static_cast<int>(floorFast(s));
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
  const int d = static_cast<int>(floorFast(f.distance / distance_step_));
  if (d < 0 || d >= distance_bins_) return false;
  auto a = [&](float x) {
    return std::clamp(static_cast<int>(floorFast(x / angle_step_)), 0, angle_bins_ - 1);
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
  // A key is linear in the four bins (pack), so every combination is a sum of one term per
  // dimension: 16 additions instead of 16 packings (this runs for every PPF check of base
  // sampling). The order is that of a 4-bit mask whose bit k picks dimension k's neighbour.
  const auto b = static_cast<uint32_t>(angle_bins_);
  const uint32_t scale[4] = {b * b * b, b * b, b, 1};
  uint32_t term[4][2];
  int options[4];
  for (int k = 0; k < 4; ++k) {
    term[k][0] = static_cast<uint32_t>(dims[k].first) * scale[k];
    options[k] = dims[k].second >= 0 ? 2 : 1;
    term[k][1] = options[k] == 2 ? static_cast<uint32_t>(dims[k].second) * scale[k] : 0;
  }
  int n = 0;
  for (int i3 = 0; i3 < options[3]; ++i3) {
    for (int i2 = 0; i2 < options[2]; ++i2) {
      const uint32_t high = term[3][i3] + term[2][i2];
      for (int i1 = 0; i1 < options[1]; ++i1) {
        for (int i0 = 0; i0 < options[0]; ++i0) out[n++] = high + term[1][i1] + term[0][i0];
      }
    }
  }
  return n;
}

}  // namespace stocs
