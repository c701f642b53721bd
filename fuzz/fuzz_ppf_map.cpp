// The PPF map inside a model cache entry, through PpfHashMap::read (fuzz_model_cache reaches it
// too, but rebuilds the model after every rejected entry, which takes seconds). Input: u16 model
// sample count, then the map as PpfHashMap::write writes it. A map that is accepted is queried
// along its whole distance range: every lookup must stay in bounds and name valid samples.
#include <sstream>

#include "byte_io.h"
#include "fuzz_support.h"
#include "stocs/model/ppf_hash_map.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  stocs::fuzz::ByteReader in(data, size);
  const size_t model_size = in.take<uint16_t>();
  const std::vector<uint8_t> rest = in.rest();
  std::istringstream map_bytes(std::string(rest.begin(), rest.end()), std::ios::binary);
  stocs::fuzz::tolerateInputError([&] {
    const stocs::PpfHashMap map = stocs::PpfHashMap::read(map_bytes, model_size);
    const Eigen::Vector3f n1 = Eigen::Vector3f::UnitZ();
    const Eigen::Vector3f n2 = Eigen::Vector3f(0, 1, 1).normalized();
    for (int step = 0; step <= 16; ++step) {
      const float d = map.minDistance() + (map.maxDistance() - map.minDistance()) * step / 16;
      const Eigen::Vector3f p2(d, 0, 0);
      map.consistent(Eigen::Vector3f::Zero(), n1, p2, n2);
      map.forEachMatch(Eigen::Vector3f::Zero(), n1, p2, n2, [&](int i, int j) {
        if (i < 0 || j < 0 || static_cast<size_t>(i) >= model_size ||
            static_cast<size_t>(j) >= model_size) {
          __builtin_trap();
        }
      });
    }
  });
  return 0;
}
