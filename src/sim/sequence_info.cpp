#include "stocs/sim/sequence_info.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "stocs/io/bop_dataset.h"
#include "stocs/util/error.h"

namespace stocs {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr SequenceEventKind kKinds[] = {SequenceEventKind::kPush, SequenceEventKind::kLift,
                                        SequenceEventKind::kRemoval, SequenceEventKind::kOcclusion};

SequenceEventKind eventKind(const fs::path& file, const std::string& name) {
  for (SequenceEventKind kind : kKinds) {
    if (sequenceEventName(kind) == name) return kind;
  }
  throw InputError(fmt::format(
      "{}: unknown event kind '{}' (known: push, lift, removal, occlusion)", file.string(), name));
}

std::map<int, double> readStamps(const fs::path& file, const json& stamps) {
  std::map<int, double> out;
  for (auto it = stamps.begin(); it != stamps.end(); ++it) {
    size_t used = 0;
    const int im = std::stoi(it.key(), &used);
    if (used != it.key().size() || im < 0) throw std::invalid_argument("image id");
    out[im] = it.value().get<double>();
  }
  double last = -INFINITY;
  for (const auto& [im, t] : out) {
    if (!(t > last)) {
      throw InputError(fmt::format("{}: the time of image {} ({} s) does not follow the one before",
                                   file.string(), im, t));
    }
    last = t;
  }
  return out;
}

SequenceEvent readEvent(const fs::path& file, const json& j) {
  SequenceEvent e;
  e.kind = eventKind(file, j.at("kind").get<std::string>());
  e.obj_id = j.at("obj_id").get<int>();
  e.first_frame = j.at("first_frame").get<int>();
  e.last_frame = j.at("last_frame").get<int>();
  if (e.last_frame < e.first_frame) {
    throw InputError(fmt::format("{}: the {} event ends (frame {}) before it starts (frame {})",
                                 file.string(), sequenceEventName(e.kind), e.last_frame,
                                 e.first_frame));
  }
  return e;
}

}  // namespace

fs::path sequenceInfoPath(const fs::path& scene_dir) {
  return scene_dir / "scene_events.json";
}

SequenceInfo evenlyTimed(const std::vector<int>& im_ids, double rate_hz) {
  SequenceInfo info;
  info.rate_hz = rate_hz;
  for (size_t k = 0; k < im_ids.size(); ++k) info.stamps[im_ids[k]] = k / rate_hz;
  return info;
}

void writeSequenceInfo(const fs::path& file, const SequenceInfo& info) {
  json stamps = json::object();
  // Microseconds: short text, and exact enough for any frame rate a camera has.
  for (const auto& [im, t] : info.stamps) stamps[std::to_string(im)] = std::round(t * 1e6) / 1e6;
  json events = json::array();
  for (const SequenceEvent& e : info.events) {
    events.push_back({{"kind", sequenceEventName(e.kind)},
                      {"obj_id", e.obj_id},
                      {"first_frame", e.first_frame},
                      {"last_frame", e.last_frame}});
  }
  std::ofstream out(file, std::ios::binary);
  out << fmt::format("{{\n \"rate_hz\": {},\n \"events\": {},\n \"stamps\": {}\n}}\n",
                     json(info.rate_hz).dump(), events.dump(), stamps.dump());
  if (!out) throw InputError(fmt::format("{}: cannot write file", file.string()));
}

SequenceInfo readSequenceInfo(const fs::path& file) {
  SequenceInfo info;
  try {
    const json j = json::parse(readTextFile(file));
    info.rate_hz = j.at("rate_hz").get<double>();
    info.stamps = readStamps(file, j.at("stamps"));
    for (const json& e : j.at("events")) info.events.push_back(readEvent(file, e));
  } catch (const json::exception& e) {
    throw InputError(
        fmt::format("{}: not a sequence's scene_events.json: {}", file.string(), e.what()));
  } catch (const std::logic_error&) {  // std::stoi: not a number, or out of range
    throw InputError(fmt::format("{}: a key of 'stamps' is not an image id", file.string()));
  }
  if (!(info.rate_hz > 0 && std::isfinite(info.rate_hz))) {
    throw InputError(
        fmt::format("{}: rate_hz {} is not a positive frame rate", file.string(), info.rate_hz));
  }
  return info;
}

std::optional<double> sequenceRate(const BopDataset& dataset, const std::vector<int>& scenes) {
  std::optional<double> rate;
  int rate_scene = 0;
  for (int scene : scenes) {
    const fs::path file = sequenceInfoPath(dataset.sceneDir(scene));
    std::error_code ec;
    if (!fs::exists(file, ec)) continue;
    const double r = readSequenceInfo(file).rate_hz;
    if (rate && *rate != r) {
      throw InputError(fmt::format(
          "{}: scene {} is a sequence at {} Hz, scene {} at {} Hz: play them apart or set a rate",
          dataset.root().string(), rate_scene, *rate, scene, r));
    }
    rate = r;
    rate_scene = scene;
  }
  return rate;
}

}  // namespace stocs
