#include "stocs_ros/common/node_config.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <map>
#include <regex>
#include <set>

#include "stocs/io/bop_dataset.h"
#include "stocs/io/mesh_io.h"
#include "stocs/util/error.h"
#include "stocs/util/param_file.h"
#include "stocs_ros/common/resource_path.h"

namespace stocs_ros {
namespace fs = std::filesystem;
using stocs::InputError;

namespace {

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
    return stocs::readYamlScalar<T>(file_, n, name);
  }

  [[noreturn]] void fail(const YAML::Node& n, const std::string& name,
                         const std::string& problem) const {
    stocs::failAtYamlNode(file_, n, name, problem);
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

stocs::ObjectSymmetries readSymmetries(MapReader reader, float unit_scale) {
  stocs::ObjectSymmetries out;
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
    stocs::SymmetryAxis c;
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

/// What models_info.json beside a BOP model file (obj_<id>.ply, in mm) declares for it, in
/// metres: none without such a file or entry.
stocs::ObjectSymmetries modelsInfoSymmetries(const fs::path& model) {
  static const std::regex bop_name(R"(obj_0*(\d+)\.\w+)");
  std::smatch id;
  const std::string name = model.filename().string();
  if (!std::regex_match(name, id, bop_name)) return {};
  const std::map<int, stocs::BopObjectInfo> info =
      stocs::readModelsInfo(model.parent_path() / "models_info.json");
  const auto entry = info.find(std::stoi(id[1]));
  return entry == info.end() ? stocs::ObjectSymmetries{} : entry->second.symmetries();
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
    if (!mesh.empty()) {
      o.mesh_url = resourceUrl(mesh, paths);
    } else if (stocs::isMeshOnlyFormat(o.model.string())) {
      o.mesh_url = "file://" + o.model.lexically_normal().string();  // rviz shows the same file
    }
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}{}: {}", where, key, e.what()));
  }
  if (reader.node("symmetries")) {
    o.symmetries = readSymmetries(reader.map("symmetries"), o.unit_scale);
  } else {
    try {
      o.symmetries = modelsInfoSymmetries(o.model);
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}symmetries from models_info.json: {}", where, e.what()));
    }
  }
  reader.rejectUnknownKeys();
  return o;
}

/// Checks a list of object names of the input section (`key`: "channels" or "labels"), used only
/// when `used`: every name is a configured object or "-", none twice, every object named.
void checkObjectList(const NodeConfig& c, const std::vector<std::string>& list,
                     const std::string& key, bool used, const std::string& when) {
  const std::string file = c.file.string();
  if (!used) {
    if (!list.empty()) {
      throw InputError(
          fmt::format("{}: input.{} is only used with input.probability: {}", file, key, when));
    }
    return;
  }
  std::set<std::string> seen;
  for (const std::string& name : list) {
    if (name == "-") continue;
    if (c.objectIndex(name) < 0) {
      throw InputError(
          fmt::format("{}: input.{} names '{}', which is not a configured "
                      "object ({}); use '-' for one to ignore",
                      file, key, name, c.objectNames()));
    }
    if (!seen.insert(name).second) {
      throw InputError(fmt::format("{}: input.{} names '{}' twice", file, key, name));
    }
  }
  for (const ObjectConfig& o : c.objects) {
    if (!seen.count(o.name) && (key == "channels" || !list.empty())) {
      throw InputError(fmt::format("{}: object '{}' has no {} in input.{}", file, o.name,
                                   key == "channels" ? "channel" : "class", key));
    }
  }
}

void checkInputLists(const NodeConfig& c) {
  checkObjectList(c, c.input.channels, "channels",
                  c.input.probability == ProbabilitySource::kMultichannel, "multichannel");
  checkObjectList(c, c.input.labels, "labels", c.input.segmentationForm(),
                  "labels, masks or boxes");
  if (c.input.label_confidence && c.input.probability != ProbabilitySource::kLabels) {
    throw InputError(fmt::format(
        "{}: input.label_confidence is only used with input.probability: labels", c.file.string()));
  }
}

/// The readers of the maps on the way to each parameter, by dotted path ("" is the root), so that
/// every map's unknown keys are rejected once all its known ones were read.
class SchemaReader {
 public:
  explicit SchemaReader(MapReader& root) : root_(root) {}

  /// Reads every parameter of `schema` present in the file into `target`, checking its type,
  /// its range and its choices, each error naming the file, the line and the key.
  template <class S>
  void read(const stocs::ParamSet<S>& schema, S& target) {
    for (const auto& entry : schema.entries()) {
      const std::string& key = entry.info.key;
      const size_t dot = key.rfind('.');
      MapReader& map = mapAt(dot == std::string::npos ? "" : key.substr(0, dot));
      const std::string name = dot == std::string::npos ? key : key.substr(dot + 1);
      const YAML::Node node = map.node(name);
      if (!node) continue;
      stocs::assignParamNode(map.file(), node, key, entry.info, entry.field(target));
    }
  }

  /// Rejects the keys of every map below the root that no parameter named.
  void rejectUnknownKeys() {
    for (auto& [path, reader] : maps_) reader.rejectUnknownKeys();
  }

  /// The reader of the map at `path` ("input.sync"; "" is the root).
  MapReader& mapAt(const std::string& path) {
    if (path.empty()) return root_;
    auto it = maps_.find(path);
    if (it != maps_.end()) return it->second;
    const size_t dot = path.rfind('.');
    MapReader& parent = mapAt(dot == std::string::npos ? "" : path.substr(0, dot));
    return maps_.emplace(path, parent.map(path.substr(dot + 1))).first->second;
  }

 private:
  MapReader& root_;
  std::map<std::string, MapReader> maps_;
};

}  // namespace

const stocs::ParamSet<InputConfig>& InputConfig::schema() {
  static const stocs::ParamSet<InputConfig> schema =
      stocs::ParamSet<InputConfig>()
          .choice(&InputConfig::depth, "source",
                  {{"cloud", DepthSource::kCloud}, {"depth", DepthSource::kDepthImage}},
                  "cloud: organized ~cloud; depth: ~depth + ~camera_info (REP 118)")
          .choice(&InputConfig::probability, "probability",
                  {{"per_object", ProbabilitySource::kPerObject},
                   {"multichannel", ProbabilitySource::kMultichannel},
                   {"labels", ProbabilitySource::kLabels},
                   {"masks", ProbabilitySource::kMasks},
                   {"boxes", ProbabilitySource::kBoxes},
                   {"geometric", ProbabilitySource::kGeometric}},
                  "per_object: ~probability/<name>; multichannel: one ~probability; labels: "
                  "~labels; masks: ~masks; boxes: ~boxes; geometric: none, maps from the depth "
                  "alone (input.geometric)")
          .add(&InputConfig::channels, "channels", "", std::nullopt,
               "multichannel: the object name of each channel in order, \"-\" to ignore one")
          .add(&InputConfig::uint16_scale, "uint16_scale", "", stocs::ParamRange::aboveUpTo(0, 1e9),
               "mono16 probability = value / uint16_scale")
          .add(&InputConfig::boundary, "boundary",
               "also wait for ~boundary (mono8, 255 interior) and use its regions")
          .add(&InputConfig::colour, "colour",
               "also wait for ~rgb, the colour image registered with the depth (rgb8, bgr8, ...), "
               "instead of a cloud's rgb field")
          .add(&InputConfig::labels, "labels", "", std::nullopt,
               "labels, masks, boxes: the object name of each class id from 0, \"-\" to ignore "
               "one; empty: class id = object id")
          .add(&InputConfig::label_confidence, "label_confidence",
               "labels: also wait for ~label_confidence (32FC1, mono16, mono8)")
          .nest(&InputConfig::segmentation, "segmentation",
                stocs::SegmentationInputParams::schema())
          .nest(&InputConfig::geometric, "geometric", stocs::GeometricSegmentationParams::schema())
          .nest(&InputConfig::sync, "sync", SyncParams::schema());
  return schema;
}

const stocs::ParamSet<OutputConfig>& OutputConfig::schema() {
  static const stocs::ParamSet<OutputConfig> schema =
      stocs::ParamSet<OutputConfig>()
          .add(&OutputConfig::frame, "frame", "", std::nullopt,
               "frame of every pose output (TF parent, ~poses, ~objects, ~pose/*, ~markers, "
               "~estimate), e.g. base_link; empty: the input's frame")
          .add(&OutputConfig::transform_timeout, "transform_timeout", "s",
               stocs::ParamRange::closed(0, 10),
               "how long to wait for the transform from the input's frame to `frame` at the "
               "input's stamp before the frame is dropped")
          .add(&OutputConfig::frame_prefix, "frame_prefix", "", std::nullopt,
               "TF child frame = frame_prefix + object name")
          .add(&OutputConfig::tf, "tf", "publish TF from the output frame to each found object")
          .add(&OutputConfig::markers, "markers", "publish ~markers")
          .add(&OutputConfig::estimate_on_frames, "estimate_on_frames",
               "false: estimate only when ~estimate is called");
  return schema;
}

const stocs::ParamSet<NodeConfig>& NodeConfig::schema() {
  static const stocs::ParamSet<NodeConfig> schema =
      stocs::ParamSet<NodeConfig>()
          .nest(&NodeConfig::input, "input", InputConfig::schema(), "Inputs")
          .nest(&NodeConfig::output, "output", OutputConfig::schema(), "Outputs")
          .add(&NodeConfig::model_cache_setting, "model_cache", "", std::nullopt,
               "folder for prepared models; empty: $XDG_CACHE_HOME/stocs_ros; none: off")
          .nest(&NodeConfig::estimation, "estimation", stocs::PipelineParams::schema())
          .nest(&NodeConfig::tracking, "tracking", stocs::TrackingParams::schema(), "Tracking");
  return schema;
}

bool InputConfig::segmentationForm() const {
  return probability == ProbabilitySource::kLabels || probability == ProbabilitySource::kMasks ||
         probability == ProbabilitySource::kBoxes;
}

int NodeConfig::classOf(size_t object) const {
  const auto it = std::find(input.labels.begin(), input.labels.end(), objects[object].name);
  return it == input.labels.end() ? objects[object].id
                                  : static_cast<int>(it - input.labels.begin());
}

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
  const YAML::Node root = stocs::loadYamlFile(file, "cannot open the configuration file");
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
  SchemaReader schema(reader);
  schema.read(NodeConfig::schema(), c);
  schema.rejectUnknownKeys();
  checkInputLists(c);
  try {
    c.input.geometric.validate();  // what the schema's ranges cannot say: min below max
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: input.geometric: {}", file.string(), e.what()));
  }
  if (c.model_cache_setting.empty()) {
    c.model_cache = stocs::ModelCache::defaultDirectory();
  } else if (c.model_cache_setting != "none") {
    c.model_cache = resolveResourcePath(c.model_cache_setting, paths);
  }
  reader.rejectUnknownKeys();
  return c;
}

}  // namespace stocs_ros
