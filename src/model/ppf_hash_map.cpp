#include "stocs/model/ppf_hash_map.h"

#include <fmt/format.h>

#include <algorithm>

#include <istream>
#include <ostream>

#include "stocs/util/error.h"

namespace stocs {
namespace {

template <class T>
void writePod(std::ostream& out, const T& v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof(T));
}
template <class T>
void writeVector(std::ostream& out, const std::vector<T>& v) {
  writePod(out, static_cast<uint64_t>(v.size()));
  out.write(reinterpret_cast<const char*>(v.data()),
            static_cast<std::streamsize>(v.size() * sizeof(T)));
}
template <class T>
T readPod(std::istream& in) {
  T v{};
  if (!in.read(reinterpret_cast<char*>(&v), sizeof(T))) throw InputError("PPF map is truncated");
  return v;
}
template <class T>
std::vector<T> readVector(std::istream& in, uint64_t max_size) {
  const uint64_t n = readPod<uint64_t>(in);
  if (n > max_size)
    throw InputError(fmt::format("PPF map array of {} entries exceeds {}", n, max_size));
  // Grown chunk by chunk as the bytes arrive: a corrupt count must not allocate gigabytes before
  // the stream turns out to be short (found by fuzz_ppf_map).
  constexpr uint64_t kChunk = 1 << 16;
  std::vector<T> v;
  while (v.size() < n) {
    const size_t done = v.size();
    v.resize(done + std::min(kChunk, n - done));
    if (!in.read(reinterpret_cast<char*>(v.data() + done),
                 static_cast<std::streamsize>((v.size() - done) * sizeof(T)))) {
      throw InputError("PPF map is truncated");
    }
  }
  return v;
}

}  // namespace

const ParamSet<PpfParams>& PpfParams::schema() {
  static const ParamSet<PpfParams> schema =
      ParamSet<PpfParams>()
          .add(&PpfParams::distance_step, "distance_step", "m", ParamRange::closed(0.0001, 0.1),
               "PPF distance bin")
          .flag("--ppf-distance-step")
          .add(&PpfParams::angle_step_deg, "angle_step_deg", "deg", ParamRange::closed(1, 45),
               "PPF angle bin")
          .flag("--ppf-angle-step")
          .add(&PpfParams::min_distance_ratio, "min_distance_ratio", "",
               ParamRange::fromBelow(0, 0.9),
               "shortest stored model pair, fraction of the diameter")
          .flag("--ppf-min-distance");
  return schema;
}

void PpfParams::validate() const {
  schema().validate(*this);
}

PpfHashMap PpfHashMap::build(const ObjectModel& model, const PpfParams& params) {
  params.validate();
  if (model.size() < 4 || model.size() > kMaxModelSamples) {
    throw InputError(
        fmt::format("PPF map needs 4 to {} model samples, got {}", kMaxModelSamples, model.size()));
  }
  PpfHashMap map;
  map.min_distance_ = params.min_distance_ratio * model.diameter;
  map.max_distance_ = model.diameter * 1.01f;  // samples of a mesh may lie a hair beyond vertices
  map.quantizer_ =
      PpfQuantizer(params.distance_step, params.angle_step_deg * static_cast<float>(M_PI) / 180.0f,
                   map.max_distance_);
  if (!map.quantizer_.keysFit()) {
    throw InputError(
        fmt::format("PPF steps {} m and {} deg give too many bins for a model of diameter {} m",
                    params.distance_step, params.angle_step_deg, model.diameter));
  }

  // Counting sort of all stored pairs by key: one pass to count, one to place.
  const uint32_t key_count = map.quantizer_.keyCount();
  std::vector<uint32_t> count(key_count + 1, 0);
  const size_t n = model.size();
  const float min2 = map.min_distance_ * map.min_distance_;
  auto forEachStoredPair = [&](auto&& emit) {
    for (size_t i = 0; i < n; ++i) {
      for (size_t j = i + 1; j < n; ++j) {
        if ((model.points[j] - model.points[i]).squaredNorm() < min2) continue;
        uint32_t key;
        if (map.quantizer_.key(
                computePpf(model.points[i], model.normals[i], model.points[j], model.normals[j]),
                key)) {
          emit(key, static_cast<uint16_t>(i), static_cast<uint16_t>(j));
        }
      }
    }
  };
  forEachStoredPair([&](uint32_t key, uint16_t, uint16_t) { ++count[key + 1]; });
  for (uint32_t k = 0; k < key_count; ++k) {
    if (count[k + 1] > 0) map.keys_.push_back(k);
    count[k + 1] += count[k];
  }
  map.pairs_.resize(count[key_count]);
  std::vector<uint32_t> cursor(count.begin(), count.end() - 1);
  forEachStoredPair([&](uint32_t key, uint16_t i, uint16_t j) {
    map.pairs_[cursor[key]++] = {i, j};
  });
  map.offsets_.reserve(map.keys_.size() + 1);
  for (uint32_t key : map.keys_) map.offsets_.push_back(count[key]);
  map.offsets_.push_back(static_cast<uint32_t>(map.pairs_.size()));
  map.buildOccupancy();
  return map;
}

void PpfHashMap::buildOccupancy() {
  occupancy_.assign((quantizer_.keyCount() + 63) / 64, 0);
  for (uint32_t key : keys_) occupancy_[key >> 6] |= 1ull << (key & 63);
}

size_t PpfHashMap::memoryBytes() const {
  return keys_.size() * sizeof(uint32_t) + offsets_.size() * sizeof(uint32_t) +
         pairs_.size() * sizeof(ModelPair) + occupancy_.size() * sizeof(uint64_t);
}

void PpfHashMap::write(std::ostream& out) const {
  writePod(out, quantizer_.distanceStep());
  writePod(out, quantizer_.angleStep());
  writePod(out, min_distance_);
  writePod(out, max_distance_);
  writeVector(out, keys_);
  writeVector(out, offsets_);
  writeVector(out, pairs_);
}

PpfHashMap PpfHashMap::read(std::istream& in, size_t model_size) {
  PpfHashMap map;
  const float distance_step = readPod<float>(in);
  const float angle_step = readPod<float>(in);
  map.min_distance_ = readPod<float>(in);
  map.max_distance_ = readPod<float>(in);
  if (!(distance_step >= 1e-4f && distance_step <= 0.1f) ||
      !(angle_step > 0.01f && angle_step < 1.0f) ||
      !(map.max_distance_ > 0 && map.max_distance_ < 20.0f) || !(map.min_distance_ >= 0) ||
      !(map.min_distance_ < map.max_distance_)) {
    throw InputError("PPF map header holds out-of-range values");
  }
  map.quantizer_ = PpfQuantizer(distance_step, angle_step, map.max_distance_);
  // Wrapped 32-bit keys would index past the occupancy bits in every lookup.
  if (!map.quantizer_.keysFit()) throw InputError("PPF map header gives too many bins");
  const uint32_t key_count = map.quantizer_.keyCount();
  map.keys_ = readVector<uint32_t>(in, key_count);
  map.offsets_ = readVector<uint32_t>(in, uint64_t{key_count} + 1);
  map.pairs_ = readVector<ModelPair>(in, uint64_t{kMaxModelSamples} * kMaxModelSamples / 2);
  // Every later lookup trusts these arrays, so check them fully.
  if (map.offsets_.size() != map.keys_.size() + 1 || map.offsets_.front() != 0 ||
      map.offsets_.back() != map.pairs_.size()) {
    throw InputError("PPF map offsets do not match its keys and pairs");
  }
  for (size_t k = 0; k < map.keys_.size(); ++k) {
    if (map.keys_[k] >= key_count || (k > 0 && map.keys_[k] <= map.keys_[k - 1]) ||
        map.offsets_[k + 1] <= map.offsets_[k]) {
      throw InputError("PPF map keys are not sorted, distinct and non-empty");
    }
  }
  for (const ModelPair& p : map.pairs_) {
    if (p.first >= model_size || p.second >= model_size || p.first == p.second) {
      throw InputError(fmt::format("PPF map pair ({}, {}) is invalid for {} model samples", p.first,
                                   p.second, model_size));
    }
  }
  map.buildOccupancy();
  return map;
}

}  // namespace stocs
