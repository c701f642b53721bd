#pragma once
// Seeded random numbers. The standard distributions are implementation-defined, so floats are
// derived from raw engine bits here: the same seed gives the same samples on every platform.

#include <cstdint>
#include <random>

namespace stocs {

using Rng = std::mt19937_64;

/// Uniform float in [0, 1).
inline float uniform01(Rng& rng) {
  return static_cast<float>(rng() >> 40) * (1.0f / 16777216.0f);
}

/// Uniform integer in [0, n), n > 0 (Lemire's multiply-shift; bias below 2^-32 for n < 2^32).
inline uint32_t uniformIndex(Rng& rng, uint32_t n) {
  return static_cast<uint32_t>(((rng() >> 32) * static_cast<uint64_t>(n)) >> 32);
}

/// Well-mixed seed for stream `index` of a run seeded with `seed` (SplitMix64 finaliser), so that
/// work item i draws the same numbers whichever thread runs it.
inline uint64_t streamSeed(uint64_t seed, uint64_t index) {
  uint64_t z = seed + 0x9E3779B97F4A7C15ull * (index + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace stocs
