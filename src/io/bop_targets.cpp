#include "stocs/io/bop_targets.h"

#include <fmt/format.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <tuple>

#include "json_fields.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/util/error.h"

namespace stocs {
using nlohmann::json;

std::vector<BopTarget> parseBopTargets(const std::string& text, const std::string& name) {
  json list;
  try {
    list = json::parse(text);
  } catch (const json::exception& e) {
    throw InputError(fmt::format("{}: invalid JSON: {}", name, e.what()));
  }
  if (!list.is_array()) {
    throw InputError(
        fmt::format("{}: a targets file is a list of {{scene_id, im_id, obj_id, inst_count}}; this "
                    "is a JSON {}",
                    name, list.type_name()));
  }
  std::vector<BopTarget> targets;
  std::map<std::tuple<int, int, int>, size_t> seen;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string where = fmt::format("{}: entry {}", name, i);
    const json& entry = list[i];
    if (!entry.is_object()) {
      throw InputError(fmt::format("{} is a JSON {}, not an object", where, entry.type_name()));
    }
    const BopTarget t{
        integerAtLeast(entry, "scene_id", 0, where), integerAtLeast(entry, "im_id", 0, where),
        integerAtLeast(entry, "obj_id", 1, where), integerAtLeast(entry, "inst_count", 0, where)};
    const auto [it, added] = seen.emplace(std::tuple{t.scene_id, t.im_id, t.obj_id}, i);
    if (!added) {
      throw InputError(fmt::format("{} repeats scene {} image {} object {} of entry {}", where,
                                   t.scene_id, t.im_id, t.obj_id, it->second));
    }
    targets.push_back(t);
  }
  return targets;
}

std::vector<BopTarget> readBopTargets(const std::filesystem::path& file) {
  return parseBopTargets(readTextFile(file), file.string());
}

void writeBopTargets(const std::filesystem::path& file, const std::vector<BopTarget>& targets) {
  std::string text = "[";
  for (size_t i = 0; i < targets.size(); ++i) {
    const BopTarget& t = targets[i];
    text +=
        fmt::format("{}\n {{\"scene_id\": {}, \"im_id\": {}, \"obj_id\": {}, \"inst_count\": {}}}",
                    i ? "," : "", t.scene_id, t.im_id, t.obj_id, t.inst_count);
  }
  text += "\n]\n";
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw InputError(fmt::format("{}: cannot write file", file.string()));
}

}  // namespace stocs
