#pragma once
// The on-disk layout of a model cache entry (model_cache.cpp), shared with the fuzz harness that
// writes entries of its own: a fixed header, then payload_size bytes of payload.

#include <cstdint>

namespace stocs::detail {

inline constexpr char kCacheMagic[8] = {'S', 'T', 'O', 'C', 'S', 'P', 'P', 'F'};

struct CacheEntryHeader {
  char magic[8];
  uint32_t version;  ///< ModelCache::kFormatVersion
  uint32_t reserved;
  uint64_t key;           ///< hash of the model bytes and the preparation parameters
  uint64_t payload_size;  ///< bytes after the header
  uint64_t payload_hash;  ///< XXH64 of the payload
};
static_assert(sizeof(CacheEntryHeader) == 40);

}  // namespace stocs::detail
