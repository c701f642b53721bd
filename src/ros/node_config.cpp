#include "stocs_ros/node_config.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <regex>
#include <set>

#include "stocs/error.h"
#include "stocs_ros/resource_path.h"

namespace stocs_ros {
namespace fs = std::filesystem;
using stocs::InputError;

namespace {

template <class T>
const char* expectedType() {
  if constexpr (std::is_same_v<T, bool>) {
    return "true or false";
  } else if constexpr (std::is_integral_v<T>) {
    return "an integer";
  } else if constexpr (std::is_floating_point_v<T>) {
    return "a number";
  } else {
    return "a string";
  }
}

/// Reads the keys of one YAML map, each named in errors by its full path ("input.sync.tolerance"),
/// and rejects keys nobody asked for, so a misspelt parameter cannot be silently ignored.
class MapReader {
 public:
  MapReader(const fs::path& file, YAML::Node node, std::string path)
      : file_(file), node_(std::move(node)), path_(std::move(path)) {
    if (node_ && !node_.IsNull() && !node_.IsMap()) fail(node_, path_, "expected a map of keys");
  }

  /// Sets `value` when `key` is present.
  template <class T>
  void get(const std::string& key, T& value) {
    const YAML::Node n = find(key);
    if (n) value = convert<T>(n, fullName(key));
  }

  /// A node (for lists), or an undefined node when absent.
  YAML::Node node(const std::string& key) { return find(key); }

  MapReader map(const std::string& key) { return MapReader(file_, find(key), fullName(key)); }

  void rejectUnknownKeys() const {
    if (!node_ || !node_.IsMap()) return;
    for (const auto& entry : node_) {
      const std::string key = entry.first.as<std::string>();
      if (!used_.count(key)) fail(entry.first, fullName(key), "unknown key");
    }
  }

  template <class T>
  T convert(const YAML::Node& n, const std::string& name) const {
    if (!n.IsScalar()) fail(n, name, fmt::format("expected {}", expectedType<T>()));
    try {
      return n.as<T>();
    } catch (const YAML::Exception&) {
      fail(n, name, fmt::format("expected {}, got '{}'", expectedType<T>(), n.Scalar()));
    }
  }

  [[noreturn]] void fail(const YAML::Node& n, const std::string& name,
                         const std::string& problem) const {
    throw InputError(
        fmt::format("{}:{}: {}: {}", file_.string(), n.Mark().line + 1, name, problem));
  }

  std::string fullName(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }

  const fs::path& file() const { return file_; }

 private:
  YAML::Node find(const std::string& key) {
    used_.insert(key);
    if (!node_ || !node_.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
    const YAML::Node& map = node_;  // the const operator[] never inserts
    return map[key];
  }

  fs::path file_;
  YAML::Node node_;
  std::string path_;
  std::set<std::string> used_;
};

template <int N>
Eigen::Matrix<float, N, 1> readVector(const MapReader& reader, const YAML::Node& n,
                                      const std::string& name) {
  if (!n.IsSequence() || n.size() != N) {
    reader.fail(n, name, fmt::format("expected a list of {} numbers", N));
  }
  Eigen::Matrix<float, N, 1> v;
  for (int i = 0; i < N; ++i) v[i] = reader.convert<float>(n[i], fmt::format("{}[{}]", name, i));
  return v;
}

ObjectSymmetries readSymmetries(MapReader reader, float unit_scale) {
  ObjectSymmetries out;
  const std::string discrete_name = reader.fullName("discrete");
  const YAML::Node discrete = reader.node("discrete");
  if (discrete && !discrete.IsSequence()) reader.fail(discrete, discrete_name, "expected a list");
  for (size_t k = 0; discrete && k < discrete.size(); ++k) {
    const std::string name = fmt::format("{}[{}]", discrete_name, k);
    const Eigen::Matrix<float, 16, 1> m = readVector<16>(reader, discrete[k], name);
    Eigen::Isometry3f s = Eigen::Isometry3f::Identity();
    s.linear() = Eigen::Map<const Eigen::Matrix<float, 4, 4, Eigen::RowMajor>>(m.data())
                     .topLeftCorner<3, 3>();
    s.translation() = Eigen::Vector3f(m[3], m[7], m[11]) * unit_scale;
    if (!(s.linear().transpose() * s.linear()).isIdentity(1e-3f) ||
        !(s.linear().determinant() > 0)) {
      reader.fail(discrete[k], name, "rotation part is not a rotation matrix (row-major 4x4)");
    }
    out.discrete.push_back(s);
  }
  const std::string continuous_name = reader.fullName("continuous");
  const YAML::Node continuous = reader.node("continuous");
  if (continuous && !continuous.IsSequence()) {
    reader.fail(continuous, continuous_name, "expected a list");
  }
  for (size_t k = 0; continuous && k < continuous.size(); ++k) {
    MapReader entry(reader.file(), continuous[k], fmt::format("{}[{}]", continuous_name, k));
    ContinuousSymmetry c;
    const YAML::Node axis = entry.node("axis");
    if (!axis) entry.fail(continuous[k], entry.fullName("axis"), "missing");
    c.axis = readVector<3>(entry, axis, entry.fullName("axis"));
    if (!(c.axis.norm() > 1e-6f)) entry.fail(axis, entry.fullName("axis"), "axis has zero length");
    c.axis.normalize();
    const YAML::Node offset = entry.node("offset");
    if (offset) c.offset = readVector<3>(entry, offset, entry.fullName("offset")) * unit_scale;
    entry.rejectUnknownKeys();
    out.continuous.push_back(c);
  }
  reader.rejectUnknownKeys();
  return out;
}

ObjectConfig readObject(MapReader reader, int position, const PathContext& paths) {
  ObjectConfig o;
  o.id = position + 1;
  std::string model, mesh;
  reader.get("name", o.name);
  reader.get("id", o.id);
  reader.get("model", model);
  reader.get("unit_scale", o.unit_scale);
  reader.get("mesh", mesh);
  o.mesh_scale = o.unit_scale;
  reader.get("mesh_scale", o.mesh_scale);
  const std::string where = fmt::format("{}: {}", reader.file().string(), reader.fullName(""));
  // Names become topic names (~probability/<name>) and TF frames: one ROS graph name token.
  static const std::regex kName("[A-Za-z][A-Za-z0-9_]*");
  if (!std::regex_match(o.name, kName)) {
    throw InputError(
        fmt::format("{}name '{}' must start with a letter and hold only letters, "
                    "digits and underscores",
                    where, o.name));
  }
  if (model.empty()) throw InputError(fmt::format("{}model is missing", where));
  if (!(o.unit_scale > 0) || !(o.mesh_scale > 0)) {
    throw InputError(fmt::format("{}unit_scale and mesh_scale must be positive", where));
  }
  std::string key = "model";  // named in the error of a path that cannot be resolved
  try {
    o.model = resolveResourcePath(model, paths);
    key = "mesh";
    if (!mesh.empty()) o.mesh_url = resourceUrl(mesh, paths);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}{}: {}", where, key, e.what()));
  }
  o.symmetries = readSymmetries(reader.map("symmetries"), o.unit_scale);
  reader.rejectUnknownKeys();
  return o;
}

void readInput(MapReader reader, InputConfig& in) {
  std::string depth = "cloud", probability = "per_object";
  reader.get("source", depth);
  reader.get("probability", probability);
  const YAML::Node channels = reader.node("channels");
  if (channels && !channels.IsSequence()) {
    reader.fail(channels, reader.fullName("channels"), "expected a list of object names");
  }
  for (size_t k = 0; channels && k < channels.size(); ++k) {
    in.channels.push_back(
        reader.convert<std::string>(channels[k], fmt::format("input.channels[{}]", k)));
  }
  reader.get("uint16_scale", in.uint16_scale);
  reader.get("boundary", in.boundary);
  MapReader sync = reader.map("sync");
  sync.get("tolerance", in.sync.tolerance);
  sync.get("queue_size", in.sync.queue_size);
  sync.get("max_age", in.sync.max_age);
  sync.rejectUnknownKeys();
  reader.rejectUnknownKeys();

  const std::string file = reader.file().string();
  if (depth == "cloud") {
    in.depth = DepthSource::kCloud;
  } else if (depth == "depth") {
    in.depth = DepthSource::kDepthImage;
  } else {
    throw InputError(fmt::format("{}: input.source '{}' must be 'cloud' or 'depth'", file, depth));
  }
  if (probability == "per_object") {
    in.probability = ProbabilitySource::kPerObject;
  } else if (probability == "multichannel") {
    in.probability = ProbabilitySource::kMultichannel;
  } else {
    throw InputError(fmt::format(
        "{}: input.probability '{}' must be 'per_object' or 'multichannel'", file, probability));
  }
  if (!(in.uint16_scale > 0)) {
    throw InputError(fmt::format("{}: input.uint16_scale must be positive", file));
  }
  try {
    in.sync.validate();
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: input.sync: {}", file, e.what()));
  }
}

void checkChannels(const NodeConfig& c) {
  const std::string file = c.file.string();
  if (c.input.probability != ProbabilitySource::kMultichannel) {
    if (!c.input.channels.empty()) {
      throw InputError(fmt::format(
          "{}: input.channels is only used with input.probability: multichannel", file));
    }
    return;
  }
  std::set<std::string> seen;
  for (const std::string& name : c.input.channels) {
    if (name == "-") continue;
    if (c.objectIndex(name) < 0) {
      throw InputError(
          fmt::format("{}: input.channels names '{}', which is not a configured "
                      "object ({}); use '-' for a channel to ignore",
                      file, name, c.objectNames()));
    }
    if (!seen.insert(name).second) {
      throw InputError(fmt::format("{}: input.channels names '{}' twice", file, name));
    }
  }
  for (const ObjectConfig& o : c.objects) {
    if (!seen.count(o.name)) {
      throw InputError(
          fmt::format("{}: object '{}' has no channel in input.channels", file, o.name));
    }
  }
}

void readEstimation(MapReader reader, stocs::PipelineParams& p) {
  MapReader segment = reader.map("segment");
  segment.get("min_probability", p.segment.min_probability);
  segment.get("voxel_size", p.segment.voxel_size);
  segment.get("samples_per_voxel", p.segment.samples_per_voxel);
  MapReader normals = segment.map("normals");
  normals.get("radius", p.segment.normals.radius);
  normals.get("samples_per_axis", p.segment.normals.samples_per_axis);
  normals.get("min_neighbours", p.segment.normals.min_neighbours);
  normals.rejectUnknownKeys();
  segment.rejectUnknownKeys();

  MapReader model = reader.map("model");
  MapReader sampling = model.map("sampling");
  sampling.get("sampling_ratio", p.model.sampling.sampling_ratio);
  sampling.get("normal_neighbours", p.model.sampling.normal_neighbours);
  sampling.get("orientation_viewpoints", p.model.sampling.orientation_viewpoints);
  sampling.rejectUnknownKeys();
  MapReader ppf = model.map("ppf");
  ppf.get("distance_step", p.model.ppf.distance_step);
  ppf.get("angle_step_deg", p.model.ppf.angle_step_deg);
  ppf.get("min_distance_ratio", p.model.ppf.min_distance_ratio);
  ppf.rejectUnknownKeys();
  model.rejectUnknownKeys();

  MapReader stocs = reader.map("stocs");
  MapReader base = stocs.map("base");
  base.get("wide_angle_deg", p.stocs.base.wide_angle_deg);
  base.get("coplanarity", p.stocs.base.coplanarity);
  base.get("max_attempts", p.stocs.base.max_attempts);
  base.get("focus_exponent", p.stocs.base.focus_exponent);
  base.rejectUnknownKeys();
  MapReader congruent = stocs.map("congruent");
  congruent.get("tolerance", p.stocs.congruent.tolerance);
  congruent.get("max_sets", p.stocs.congruent.max_sets);
  congruent.get("min_line_angle_deg", p.stocs.congruent.min_line_angle_deg);
  congruent.rejectUnknownKeys();
  stocs.get("max_fit_rms", p.stocs.max_fit_rms);
  stocs.get("duplicate_distance", p.stocs.duplicate_distance);
  stocs.get("min_normal_agreement", p.stocs.min_normal_agreement);
  stocs.get("finished_per_base", p.stocs.finished_per_base);
  MapReader lcp = stocs.map("lcp");
  lcp.get("distance", p.stocs.lcp.distance);
  lcp.get("normal_angle_deg", p.stocs.lcp.normal_angle_deg);
  lcp.get("coarse_fraction", p.stocs.lcp.coarse_fraction);
  lcp.get("coarse_ratio", p.stocs.lcp.coarse_ratio);
  lcp.rejectUnknownKeys();
  MapReader icp = stocs.map("icp");
  icp.get("enabled", p.stocs.icp.enabled);
  icp.get("iterations", p.stocs.icp.iterations);
  icp.get("max_distance", p.stocs.icp.max_distance);
  icp.get("normal_angle_deg", p.stocs.icp.normal_angle_deg);
  icp.get("candidates", p.stocs.icp.candidates);
  icp.get("screening_iterations", p.stocs.icp.screening_iterations);
  icp.get("finalists", p.stocs.icp.finalists);
  icp.rejectUnknownKeys();
  MapReader free_space = stocs.map("free_space");
  free_space.get("enabled", p.stocs.free_space.enabled);
  free_space.get("margin", p.stocs.free_space.margin);
  free_space.rejectUnknownKeys();
  stocs.get("bases", p.stocs.bases);
  stocs.get("base_draw_budget", p.stocs.base_draw_budget);
  stocs.get("focused_bases", p.stocs.focused_bases);
  stocs.get("consensus_bases", p.stocs.consensus_bases);
  stocs.get("time_budget", p.stocs.time_budget);
  stocs.get("seed", p.stocs.seed);
  stocs.get("threads", p.stocs.threads);
  stocs.get("instances", p.stocs.instances);
  stocs.get("instance_separation", p.stocs.instance_separation);
  stocs.rejectUnknownKeys();
  reader.rejectUnknownKeys();
  try {
    p.validate();
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: estimation: {}", reader.file().string(), e.what()));
  }
}

}  // namespace

int NodeConfig::objectIndex(const std::string& name) const {
  for (size_t i = 0; i < objects.size(); ++i) {
    if (objects[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

std::string NodeConfig::objectNames() const {
  std::string out;
  for (const ObjectConfig& o : objects) out += (out.empty() ? "" : ", ") + o.name;
  return out;
}

NodeConfig loadNodeConfig(const fs::path& file, const fs::path& dataset) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(file.string());
  } catch (const YAML::BadFile&) {
    throw InputError(fmt::format("{}: cannot open the configuration file", file.string()));
  } catch (const YAML::Exception& e) {
    throw InputError(fmt::format("{}: invalid YAML: {}", file.string(), e.what()));
  }
  NodeConfig c;
  c.file = fs::absolute(file);
  const PathContext paths{c.file.parent_path(), dataset};
  MapReader reader(file, root, "");

  const YAML::Node objects = reader.node("objects");
  if (!objects || !objects.IsSequence() || objects.size() == 0) {
    throw InputError(fmt::format("{}: 'objects' must be a non-empty list", file.string()));
  }
  std::set<std::string> names;
  std::set<int> ids;
  for (size_t k = 0; k < objects.size(); ++k) {
    c.objects.push_back(readObject(MapReader(file, objects[k], fmt::format("objects[{}]", k)),
                                   static_cast<int>(k), paths));
    if (!names.insert(c.objects.back().name).second || !ids.insert(c.objects.back().id).second) {
      throw InputError(fmt::format("{}: objects[{}] repeats the name '{}' or the id {}",
                                   file.string(), k, c.objects.back().name, c.objects.back().id));
    }
  }
  readInput(reader.map("input"), c.input);
  checkChannels(c);

  MapReader output = reader.map("output");
  output.get("frame_prefix", c.output.frame_prefix);
  output.get("tf", c.output.tf);
  output.get("markers", c.output.markers);
  output.get("estimate_on_frames", c.output.estimate_on_frames);
  output.rejectUnknownKeys();

  std::string cache;
  reader.get("model_cache", cache);
  if (cache.empty()) {
    c.model_cache = stocs::ModelCache::defaultDirectory();
  } else if (cache != "none") {
    c.model_cache = resolveResourcePath(cache, paths);
  }

  readEstimation(reader.map("estimation"), c.estimation);
  reader.rejectUnknownKeys();
  return c;
}

}  // namespace stocs_ros
