// The PPF model cache file through ModelCache::load, which must load a valid entry and detect,
// report and rebuild any other one, never crash. Inputs starting with an even byte are the whole
// entry file; with an odd byte the rest is a payload behind a header with the right magic, key and
// checksum, so the fuzzer reaches the payload parser (samples, normals, PPF map) directly.
#include <xxhash.h>

#include "fuzz_support.h"
#include "model_cache_setup.h"

namespace {

struct Setup {
  std::string model_file = stocs::fuzz::writeCacheFuzzModel(stocs::fuzz::scratchDir());
  stocs::ModelPreparationParams params = stocs::fuzz::cacheFuzzParams();
  stocs::ModelCache cache{stocs::fuzz::scratchDir() / "cache"};
  std::filesystem::path entry =
      cache.entryPath(model_file, stocs::fuzz::kCacheModelUnitScale, params);
};

std::string entryBytes(const uint8_t* data, size_t size, uint64_t key) {
  const std::string rest(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (data[0] % 2 == 0) return rest;
  stocs::fuzz::CacheEntryHeader h{};
  std::memcpy(h.magic, stocs::detail::kCacheMagic, sizeof h.magic);
  h.version = stocs::ModelCache::kFormatVersion;
  h.key = key;
  h.payload_size = rest.size();
  h.payload_hash = XXH64(rest.data(), rest.size(), 0);
  return std::string(reinterpret_cast<const char*>(&h), sizeof h) + rest;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const Setup setup;
  if (size == 0) return 0;
  const std::string bytes = entryBytes(data, size, stocs::fuzz::entryKeyFromName(setup.entry));
  stocs::fuzz::writeInput(setup.entry, reinterpret_cast<const uint8_t*>(bytes.data()),
                          bytes.size());
  stocs::CacheReport report;
  // Cache problems never throw: they show in the report and the model is rebuilt.
  const stocs::PreparedModel m =
      setup.cache.load(setup.model_file, stocs::fuzz::kCacheModelUnitScale, setup.params, &report);
  if (m.model.size() < 4 || m.model.points.size() != m.model.normals.size()) __builtin_trap();
  return 0;
}
