#include "stocs/io/box_files.h"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "json_fields.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/util/error.h"

namespace stocs {
using nlohmann::json;

namespace {

json parseJson(const std::string& text, const std::string& name) {
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    throw InputError(fmt::format("{}: invalid JSON: {}", name, e.what()));
  }
}

/// `[x, y, width, height]` at `key`: four finite numbers.
cv::Rect2f boxAt(const json& entry, const char* key, const std::string& where) {
  if (!entry.contains(key)) throw InputError(fmt::format("{}: missing key '{}'", where, key));
  const json& b = entry.at(key);
  bool ok = b.is_array() && b.size() == 4;
  for (size_t k = 0; ok && k < 4; ++k) ok = b[k].is_number() && std::isfinite(b[k].get<double>());
  if (!ok) {
    throw InputError(
        fmt::format("{}: '{}' is {}; it must be [x, y, width, height]", where, key, b.dump()));
  }
  return {b[0].get<float>(), b[1].get<float>(), b[2].get<float>(), b[3].get<float>()};
}

BoxDetection detectionAt(const json& entry, const std::string& where) {
  if (!entry.is_object()) {
    throw InputError(fmt::format("{} is a JSON {}, not an object", where, entry.type_name()));
  }
  BoxDetection d;
  d.class_id = integerAtLeast(entry, "category_id", 1, where);
  d.box = boxAt(entry, "bbox", where);
  if (!(d.box.width > 0 && d.box.height > 0)) {
    throw InputError(fmt::format("{}: 'bbox' has width {} and height {}; both must be positive",
                                 where, d.box.width, d.box.height));
  }
  if (!entry.contains("score") || !entry.at("score").is_number() ||
      !(entry.at("score").get<double>() >= 0 && entry.at("score").get<double>() <= 1)) {
    throw InputError(fmt::format("{}: 'score' is {}; it must be a number in [0, 1]", where,
                                 entry.contains("score") ? entry.at("score").dump() : "missing"));
  }
  d.score = entry.at("score").get<float>();
  return d;
}

}  // namespace

FrameBoxes parseBoxDetections(const std::string& text, const std::string& name) {
  const json list = parseJson(text, name);
  if (!list.is_array()) {
    throw InputError(fmt::format(
        "{}: a boxes file is a list of {{scene_id, image_id, category_id, bbox, score}}; this is "
        "a JSON {}",
        name, list.type_name()));
  }
  FrameBoxes boxes;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string where = fmt::format("{}: entry {}", name, i);
    const BoxDetection d = detectionAt(list[i], where);
    const int scene = integerAtLeast(list[i], "scene_id", 0, where);
    const int image = integerAtLeast(list[i], "image_id", 0, where);
    boxes[{scene, image}].push_back(d);
  }
  return boxes;
}

FrameBoxes readBoxDetections(const std::filesystem::path& file) {
  return parseBoxDetections(readTextFile(file), file.string());
}

std::map<int, std::vector<cv::Rect2f>> readVisibleBoxes(const std::filesystem::path& file) {
  const json images = parseJson(readTextFile(file), file.string());
  if (!images.is_object()) {
    throw InputError(fmt::format("{}: expected a JSON object keyed by image id, got a {}",
                                 file.string(), images.type_name()));
  }
  std::map<int, std::vector<cv::Rect2f>> boxes;
  for (const auto& [key, instances] : images.items()) {
    int im_id = 0;
    try {
      im_id = std::stoi(key);
    } catch (const std::exception&) {
      throw InputError(fmt::format("{}: key '{}' is not an image id", file.string(), key));
    }
    if (!instances.is_array()) {
      throw InputError(fmt::format("{}: image {} is not a list of instances", file.string(), key));
    }
    for (size_t i = 0; i < instances.size(); ++i) {
      const std::string where = fmt::format("{}: image {} instance {}", file.string(), key, i);
      if (!instances[i].is_object()) throw InputError(where + " is not an object");
      boxes[im_id].push_back(boxAt(instances[i], "bbox_visib", where));
    }
  }
  return boxes;
}

}  // namespace stocs
