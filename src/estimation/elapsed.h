#pragma once
// The wall time of a stage (PoseEstimate::stages) or of a search.

#include <chrono>

namespace stocs {

inline double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace stocs
