#pragma once
// Open-addressing hash table from packed voxel cell keys (voxel_key.h) to ranges of an array: the
// index structure behind PointGrid and NeighbourhoodGrid. Linear probing on a power-of-two table at
// most half full, doubling when an insertion would pass that; no deletion.

#include <cstdint>
#include <vector>

namespace stocs {

class CellTable {
 public:
  struct Range {
    uint32_t begin = 0, end = 0;
  };

  /// Empties the table and sizes it for `cells` keys (more may be inserted: it grows).
  void reserve(size_t cells) {
    size_t capacity = 16;
    shift_ = 60;
    while (capacity < 2 * cells) {
      capacity *= 2;
      --shift_;
    }
    mask_ = capacity - 1;
    size_ = 0;
    slots_.assign(capacity, Slot{});
  }

  /// The range of `key`, inserted empty if absent. An insertion may move every range, so a
  /// reference is valid until the next insertion.
  Range& findOrInsert(uint64_t key) {
    if (slots_.empty()) reserve(8);
    for (uint64_t h = hash(key);; h = (h + 1) & mask_) {
      Slot& slot = slots_[h];
      if (slot.key == key) return slot.range;
      if (slot.key != kEmpty) continue;
      if (2 * (size_ + 1) > slots_.size()) {
        grow();
        return findOrInsert(key);
      }
      ++size_;
      slot.key = key;
      return slot.range;
    }
  }

  size_t size() const { return size_; }

  /// The range of `key`, or nullptr.
  const Range* find(uint64_t key) const {
    if (slots_.empty()) return nullptr;
    for (uint64_t h = hash(key);; h = (h + 1) & mask_) {
      const Slot& slot = slots_[h];
      if (slot.key == key) return &slot.range;
      if (slot.key == kEmpty) return nullptr;
    }
  }

  /// Calls f(range) for every occupied slot, in slot order.
  template <class F>
  void forEachRange(F&& f) {
    for (Slot& slot : slots_) {
      if (slot.key != kEmpty) f(slot.range);
    }
  }

 private:
  static constexpr uint64_t kEmpty = ~0ull;
  // Key and range side by side: a lookup touches one cache line.
  struct Slot {
    uint64_t key = kEmpty;
    Range range;
  };

  void grow() {
    std::vector<Slot> slots = std::move(slots_);
    reserve(slots.size());  // doubles the capacity
    for (const Slot& slot : slots) {
      if (slot.key != kEmpty) findOrInsert(slot.key) = slot.range;
    }
  }

  uint64_t hash(uint64_t key) const { return (key * 0x9E3779B97F4A7C15ull) >> shift_; }

  std::vector<Slot> slots_;
  uint64_t mask_ = 0;
  size_t size_ = 0;
  int shift_ = 64;
};

}  // namespace stocs
