#include "stocs/sim/lookalikes.h"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "stocs/util/error.h"

namespace stocs {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

/// Records the pair {a, b} both ways.
void addPair(Lookalikes& lookalikes, int a, int b) {
  lookalikes[a].insert(b);
  lookalikes[b].insert(a);
}

/// The pair of one "pairs" entry; throws InputError naming the file unless it is two different
/// positive integers.
std::pair<int, int> readPair(const json& entry, const fs::path& file) {
  const bool ids = entry.is_array() && entry.size() == 2 && entry[0].is_number_integer() &&
                   entry[1].is_number_integer();
  if (!ids || entry[0].get<int>() <= 0 || entry[1].get<int>() <= 0 || entry[0] == entry[1]) {
    throw InputError(fmt::format("{}: pair {} is not two different positive object ids",
                                 file.string(), entry.dump()));
  }
  return {entry[0].get<int>(), entry[1].get<int>()};
}

}  // namespace

Lookalikes catalogueLookalikes(const std::vector<CatalogueObject>& objects) {
  std::set<int> ids;
  for (const CatalogueObject& o : objects) ids.insert(o.id);
  Lookalikes lookalikes;
  for (const CatalogueObject& o : objects) {
    for (int other : o.lookalikes) {
      if (ids.count(other) && other != o.id) addPair(lookalikes, o.id, other);
    }
  }
  return lookalikes;
}

fs::path lookalikesPath(const fs::path& root) {
  return root / "models" / "lookalikes.json";
}

void writeLookalikes(const fs::path& file, const Lookalikes& lookalikes) {
  json pairs = json::array();
  for (const auto& [a, others] : lookalikes) {
    for (int b : others) {
      if (a < b) pairs.push_back({a, b});
    }
  }
  std::ofstream out(file, std::ios::binary);
  out << json{{"pairs", pairs}}.dump() << "\n";
  if (!out) throw InputError(fmt::format("{}: cannot write file", file.string()));
}

Lookalikes readLookalikes(const fs::path& file) {
  std::error_code ec;
  if (!fs::exists(file, ec)) return {};
  std::ifstream in(file, std::ios::binary);
  const json j = json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("pairs") || !j["pairs"].is_array()) {
    throw InputError(
        fmt::format("{}: not a look-alike file (a JSON object with a \"pairs\" list of [id, id])",
                    file.string()));
  }
  Lookalikes lookalikes;
  for (const json& entry : j["pairs"]) {
    const auto [a, b] = readPair(entry, file);
    addPair(lookalikes, a, b);
  }
  return lookalikes;
}

bool boxesLookAlike(Eigen::Vector3f a, Eigen::Vector3f b, float tolerance) {
  std::sort(a.data(), a.data() + 3);
  std::sort(b.data(), b.data() + 3);
  for (int k = 0; k < 3; ++k) {
    if (std::abs(a[k] - b[k]) > tolerance * std::max(a[k], b[k])) return false;
  }
  return true;
}

}  // namespace stocs
