#include "stocs/estimation/stages/boundary_regions.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <opencv2/core.hpp>

#include "stocs/util/error.h"

// The 8-pixel steps read pixels as the bytes of a little-endian word.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "BoundaryRegions assumes little-endian");

namespace stocs {
namespace {

/// Root of run i, halving the path on the way.
int findRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

}  // namespace

BoundaryRegions::BoundaryRegions(const cv::Mat& boundary_map)
    : width_(boundary_map.cols), height_(boundary_map.rows) {
  if (boundary_map.type() != CV_8UC1 || boundary_map.empty()) {
    throw InputError(
        "boundary map must be a non-empty single-channel 8-bit image (255 interior, 0 boundary)");
  }
  // Interior is the top bit: 8 pixels whose top bits all equal the current state are skipped at
  // once, and otherwise the scan jumps to the first that differs.
  constexpr uint64_t kTopBits = 0x8080808080808080ull;
  row_starts_.reserve(static_cast<size_t>(height_) + 1);
  row_starts_.push_back(0);
  std::vector<int> parent;
  for (int v = 0; v < height_; ++v) {
    const auto* row = boundary_map.ptr<uint8_t>(v);
    bool inside = false;
    int begin = 0;
    for (int u = 0; u < width_;) {
      if (u + 8 <= width_) {
        uint64_t eight;
        std::memcpy(&eight, row + u, sizeof eight);
        const uint64_t changed = (eight & kTopBits) ^ (inside ? kTopBits : 0);
        if (changed == 0) {
          u += 8;
          continue;
        }
        u += __builtin_ctzll(changed) / 8;  // the first pixel that changes (little-endian load)
      }
      const bool interior = row[u] >= 128;
      if (interior && !inside) begin = u;
      if (!interior && inside) runs_.push_back({begin, u, 0});
      inside = interior;
      ++u;
    }
    if (inside) runs_.push_back({begin, width_, 0});
    row_starts_.push_back(static_cast<int>(runs_.size()));

    // Join each new run with the runs of the row above that share a column (4-connectivity); the
    // root of a component is its first run in raster order.
    const int first = row_starts_[static_cast<size_t>(v)], end = row_starts_.back();
    for (int i = first; i < end; ++i) parent.push_back(i);
    if (v == 0) continue;
    int above = row_starts_[static_cast<size_t>(v) - 1];
    for (int i = first; i < end; ++i) {
      const Run& run = runs_[static_cast<size_t>(i)];
      while (above < first && runs_[static_cast<size_t>(above)].end <= run.begin) ++above;
      for (int a = above; a < first && runs_[static_cast<size_t>(a)].begin < run.end; ++a) {
        const int ra = findRoot(parent, a), ri = findRoot(parent, i);
        if (ra < ri) parent[static_cast<size_t>(ri)] = ra;
        if (ri < ra) parent[static_cast<size_t>(ra)] = ri;
      }
    }
  }
  // A root precedes the other runs of its component: numbering roots in run order numbers the
  // components in raster order of their first pixel.
  for (size_t i = 0; i < runs_.size(); ++i) {
    const auto root = static_cast<size_t>(findRoot(parent, static_cast<int>(i)));
    runs_[i].region = root == i ? ++count_ : runs_[root].region;
  }
}

int BoundaryRegions::at(int u, int v) const {
  const auto first = runs_.begin() + row_starts_[static_cast<size_t>(v)];
  const auto last = runs_.begin() + row_starts_[static_cast<size_t>(v) + 1];
  // The last run beginning at or before u.
  const auto after =
      std::upper_bound(first, last, u, [](int c, const Run& r) { return c < r.begin; });
  if (after == first) return 0;
  const Run& run = *(after - 1);
  return u < run.end ? run.region : 0;
}

}  // namespace stocs
