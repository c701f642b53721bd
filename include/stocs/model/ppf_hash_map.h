#pragma once
// The model's point-pair-feature map: for every discretised PPF, the model point pairs that show
// it. It gives the paper's edge potential phi (is this scene pair's PPF on the model at all?) and
// the candidate model pairs for congruent-set extraction, with one and the same test, so a base
// whose pairs pass phi always has pairs to look up.
//
// Layout (compact, built once per model, cached on disk): each unordered model pair is stored once,
// under the key of its orientation (i < j), in sorted arrays (key list, offsets, 16-bit index
// pairs); a bitset over all keys answers "is any pair here" in O(1) without touching the arrays.
// Queries look at the 2^4 nearest bins of the scene feature in both orientations.

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <iosfwd>
#include <vector>

#include "stocs/model/object_model.h"
#include "stocs/model/ppf.h"
#include "stocs/util/param_set.h"

namespace stocs {

struct PpfParams {
  float distance_step = 0.005f;  ///< metres (paper: 0.5 cm)
  float angle_step_deg = 10.0f;  ///< degrees (paper: 10)
  /// Pairs shorter than this fraction of the diameter are left out: such short base edges
  /// determine a rotation poorly and are the pairs that most often come from one noisy patch.
  float min_distance_ratio = 0.1f;

  /// Key, range, unit and meaning of every field (docs/parameters.md).
  static const ParamSet<PpfParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
};

struct ModelPair {
  uint16_t first;
  uint16_t second;
};

class PpfHashMap {
 public:
  PpfHashMap() = default;
  static PpfHashMap build(const ObjectModel& model, const PpfParams& params);

  /// Edge potential phi: true when some model pair, in either orientation, falls into one of the
  /// nearest bins of PPF(p1, p2) and the pair length is within the stored range.
  bool consistent(const Eigen::Vector3f& p1, const Eigen::Vector3f& n1, const Eigen::Vector3f& p2,
                  const Eigen::Vector3f& n2) const {
    const float d2 = (p2 - p1).squaredNorm();
    if (d2 < min_distance_ * min_distance_ || d2 > max_distance_ * max_distance_) return false;
    PpfQuantizer::Keys keys;
    return anyOccupied(keys, quantizer_.nearestKeys(computePpf(p1, n1, p2, n2), keys)) ||
           anyOccupied(keys, quantizer_.nearestKeys(computePpf(p2, n2, p1, n1), keys));
  }

  /// Calls visit(i, j) for every ordered model pair whose PPF falls into one of the nearest bins of
  /// PPF(p1, p2): candidate correspondences p1 <-> m_i, p2 <-> m_j. Each ordered pair comes once.
  template <class Visit>
  void forEachMatch(const Eigen::Vector3f& p1, const Eigen::Vector3f& n1, const Eigen::Vector3f& p2,
                    const Eigen::Vector3f& n2, Visit&& visit) const {
    const float d2 = (p2 - p1).squaredNorm();
    if (d2 < min_distance_ * min_distance_ || d2 > max_distance_ * max_distance_) return;
    PpfQuantizer::Keys keys;
    const int forward = quantizer_.nearestKeys(computePpf(p1, n1, p2, n2), keys);
    for (int k = 0; k < forward; ++k) {
      for (const ModelPair& p : pairsWithKey(keys[k])) visit(p.first, p.second);
    }
    const int backward = quantizer_.nearestKeys(computePpf(p2, n2, p1, n1), keys);
    for (int k = 0; k < backward; ++k) {
      for (const ModelPair& p : pairsWithKey(keys[k])) visit(p.second, p.first);
    }
  }

  const PpfQuantizer& quantizer() const { return quantizer_; }
  float minDistance() const { return min_distance_; }
  float maxDistance() const { return max_distance_; }
  size_t pairCount() const { return pairs_.size(); }
  size_t occupiedKeyCount() const { return keys_.size(); }
  size_t memoryBytes() const;

  /// Binary serialisation of the map (the cache adds versioning and a checksum around it).
  void write(std::ostream& out) const;
  /// Reads what write() wrote for a model of `model_size` samples; throws InputError on any
  /// inconsistency (so a corrupt file can never send a lookup out of bounds).
  static PpfHashMap read(std::istream& in, size_t model_size);

 private:
  struct PairRange {
    const ModelPair* begin_;
    const ModelPair* end_;
    const ModelPair* begin() const { return begin_; }
    const ModelPair* end() const { return end_; }
  };

  bool occupied(uint32_t key) const { return (occupancy_[key >> 6] >> (key & 63)) & 1u; }
  bool anyOccupied(const PpfQuantizer::Keys& keys, int n) const {
    for (int k = 0; k < n; ++k) {
      if (occupied(keys[k])) return true;
    }
    return false;
  }
  PairRange pairsWithKey(uint32_t key) const {
    if (!occupied(key)) return {nullptr, nullptr};
    const size_t k = std::lower_bound(keys_.begin(), keys_.end(), key) - keys_.begin();
    return {pairs_.data() + offsets_[k], pairs_.data() + offsets_[k + 1]};
  }
  void buildOccupancy();

  PpfQuantizer quantizer_;
  float min_distance_ = 0, max_distance_ = 0;
  std::vector<uint32_t> keys_;     // sorted distinct keys that hold pairs
  std::vector<uint32_t> offsets_;  // pairs of keys_[k]: pairs_[offsets_[k] .. offsets_[k + 1])
  std::vector<ModelPair> pairs_;
  std::vector<uint64_t> occupancy_;  // one bit per key of the quantizer
};

}  // namespace stocs
