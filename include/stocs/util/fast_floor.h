#pragma once
// std::floor and std::ceil for the grids' and the PPF quantizer's inner loops. Without SSE4.1
// (the x86-64 baseline this package builds for) the compiler turns std::floor into a libm call;
// these are a conversion and a compare, exact for every float.

#include <cmath>

namespace stocs {

inline float floorFast(float x) {
  // From 2^23 on every float is an integer (and NaN and infinities pass through unchanged).
  if (!(std::abs(x) < 8388608.0f)) return x;
  const auto t = static_cast<float>(static_cast<int>(x));  // truncation toward zero
  return t > x ? t - 1.0f : t;
}

inline float ceilFast(float x) {
  return -floorFast(-x);
}

}  // namespace stocs
