#include "stocs/model/model_cache.h"

#include <fmt/format.h>
#include <unistd.h>
#include <xxhash.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "model_cache_format.h"
#include "stocs/io/mesh_io.h"
#include "stocs/util/error.h"

namespace stocs {

const ParamSet<ModelPreparationParams>& ModelPreparationParams::schema() {
  static const ParamSet<ModelPreparationParams> schema =
      ParamSet<ModelPreparationParams>()
          .nest(&ModelPreparationParams::sampling, "sampling", ModelSamplingParams::schema())
          .nest(&ModelPreparationParams::ppf, "ppf", PpfParams::schema());
  return schema;
}

void ModelPreparationParams::validate() const {
  schema().validate(*this);
}
namespace {

using detail::CacheEntryHeader;
using detail::kCacheMagic;

std::string readFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("model {}: cannot open for reading", path));
  return std::string(std::istreambuf_iterator<char>(in), {});
}

template <class T>
void appendBytes(std::string& bytes, const std::vector<T>& values) {
  bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

/// What an entry's key hashes of the model: the file's bytes and, for the formats that refer to
/// files of their own (a glTF's .bin buffers, an OBJ's .mtl, their and a COLLADA file's
/// textures), also the geometry and colours read from it, so that a changed buffer, material or
/// texture changes the key. PLY, PCD, STL and GLB hold everything in the one file.
std::string modelKeyBytes(const std::string& model_file, float unit_scale) {
  std::string bytes = readFileBytes(model_file);
  std::string ext = std::filesystem::path(model_file).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext != ".gltf" && ext != ".obj" && ext != ".dae") return bytes;
  const MeshData mesh = loadMesh(model_file, unit_scale);
  appendBytes(bytes, mesh.vertices);
  appendBytes(bytes, mesh.triangles);
  appendBytes(bytes, mesh.colours);
  return bytes;
}

uint64_t entryKey(const std::string& model_bytes, float unit_scale,
                  const ModelPreparationParams& p) {
  std::ostringstream tag;
  tag.precision(9);
  tag << ModelCache::kFormatVersion << ' ' << unit_scale << ' ' << p.sampling.sampling_ratio << ' '
      << p.sampling.normal_neighbours << ' ' << p.sampling.orientation_viewpoints << ' '
      << p.ppf.distance_step << ' ' << p.ppf.angle_step_deg << ' ' << p.ppf.min_distance_ratio;
  const std::string t = tag.str();
  return XXH64(t.data(), t.size(), XXH64(model_bytes.data(), model_bytes.size(), 0));
}

void writeVectors(std::ostream& out, const std::vector<Eigen::Vector3f>& v) {
  const uint64_t n = v.size();
  out.write(reinterpret_cast<const char*>(&n), sizeof n);
  out.write(reinterpret_cast<const char*>(v.data()),
            static_cast<std::streamsize>(n * sizeof(v[0])));
}

/// Vectors written by writeVectors, each accepted by `valid`.
template <class Valid>
std::vector<Eigen::Vector3f> readVectors(std::istream& in, Valid valid) {
  uint64_t n = 0;
  if (!in.read(reinterpret_cast<char*>(&n), sizeof n) || n > kMaxModelSamples) {
    throw InputError("model sample count is missing or out of range");
  }
  std::vector<Eigen::Vector3f> v(n);
  if (!in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(v[0])))) {
    throw InputError("model samples are truncated");
  }
  for (const Eigen::Vector3f& x : v) {
    if (!valid(x)) throw InputError("model samples hold an invalid value");
  }
  return v;
}

std::vector<Eigen::Vector3f> readVectors(std::istream& in) {
  return readVectors(in, [](const Eigen::Vector3f& x) { return x.allFinite(); });
}

/// Colours: unknown, or every component in [0, 1].
std::vector<Colour> readColours(std::istream& in) {
  return readVectors(
      in, [](const Colour& c) { return !isKnown(c) || (c.minCoeff() >= 0 && c.maxCoeff() <= 1); });
}

std::string serialise(const PreparedModel& m) {
  std::ostringstream out(std::ios::binary);
  out.write(reinterpret_cast<const char*>(&m.model.diameter), sizeof(float));
  out.write(reinterpret_cast<const char*>(&m.model.sampling_radius), sizeof(float));
  const uint8_t even = m.model.even_sampling ? 1 : 0;
  out.write(reinterpret_cast<const char*>(&even), sizeof(even));
  writeVectors(out, m.model.points);
  writeVectors(out, m.model.normals);
  writeVectors(out, m.model.colours);
  m.ppf_map.write(out);
  return out.str();
}

PreparedModel deserialise(const std::string& payload) {
  std::istringstream in(payload, std::ios::binary);
  PreparedModel m;
  if (!in.read(reinterpret_cast<char*>(&m.model.diameter), sizeof(float)) ||
      !in.read(reinterpret_cast<char*>(&m.model.sampling_radius), sizeof(float))) {
    throw InputError("header values are truncated");
  }
  if (!(m.model.diameter > 0) || !(m.model.sampling_radius > 0)) {
    throw InputError("diameter or sampling radius is not positive");
  }
  uint8_t even = 0;
  if (!in.read(reinterpret_cast<char*>(&even), sizeof(even)) || even > 1) {
    throw InputError("the even-sampling flag is missing or not 0 or 1");
  }
  m.model.even_sampling = even == 1;
  m.model.points = readVectors(in);
  m.model.normals = readVectors(in);
  if (m.model.points.size() != m.model.normals.size() || m.model.points.size() < 4) {
    throw InputError("point and normal counts differ or are too small");
  }
  m.model.colours = readColours(in);
  if (m.model.hasColour() && m.model.colours.size() != m.model.size()) {
    throw InputError("colour and point counts differ");
  }
  m.ppf_map = PpfHashMap::read(in, m.model.size());
  if (in.peek() != std::char_traits<char>::eof()) throw InputError("trailing bytes after the map");
  return m;
}

/// The entry's model, or an InputError saying why it cannot be trusted.
PreparedModel readEntry(const std::filesystem::path& file, uint64_t key) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("cannot be opened");
  CacheEntryHeader h{};
  if (!in.read(reinterpret_cast<char*>(&h), sizeof h)) throw InputError("header is truncated");
  if (std::memcmp(h.magic, kCacheMagic, sizeof kCacheMagic) != 0)
    throw InputError("not a stocs cache file");
  if (h.version != ModelCache::kFormatVersion) {
    throw InputError(
        fmt::format("format version {} is not {}", h.version, ModelCache::kFormatVersion));
  }
  if (h.key != key) throw InputError("entry belongs to other model bytes or parameters");
  // Compared with the file before allocating: a corrupt size must not allocate gigabytes.
  const std::streamoff payload_start = in.tellg();
  in.seekg(0, std::ios::end);
  const uint64_t available = static_cast<uint64_t>(in.tellg() - payload_start);
  in.seekg(payload_start);
  if (h.payload_size > available) {
    throw InputError(fmt::format("payload is truncated ({} bytes announced, {} present)",
                                 h.payload_size, available));
  }
  std::string payload(h.payload_size, '\0');
  if (!in.read(payload.data(), static_cast<std::streamsize>(payload.size()))) {
    throw InputError("payload is truncated");
  }
  if (XXH64(payload.data(), payload.size(), 0) != h.payload_hash) {
    throw InputError("payload checksum does not match");
  }
  return deserialise(payload);
}

/// Writes atomically; returns an empty string or what went wrong.
std::string writeEntry(const std::filesystem::path& file, uint64_t key, const PreparedModel& m) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  if (ec) return fmt::format("cannot create {}: {}", file.parent_path().string(), ec.message());
  const std::string payload = serialise(m);
  CacheEntryHeader h{};
  std::memcpy(h.magic, kCacheMagic, sizeof kCacheMagic);
  h.version = ModelCache::kFormatVersion;
  h.key = key;
  h.payload_size = payload.size();
  h.payload_hash = XXH64(payload.data(), payload.size(), 0);
  const fs::path tmp = file.string() + fmt::format(".tmp{}", ::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(&h), sizeof h);
    out.write(payload.data(), static_cast<std::streamsize>(payload.size()));
    if (!out) {
      fs::remove(tmp, ec);
      return fmt::format("cannot write {}", tmp.string());
    }
  }
  fs::rename(tmp, file, ec);
  if (ec) {
    fs::remove(tmp, ec);
    return fmt::format("cannot rename into {}: {}", file.string(), ec.message());
  }
  return {};
}

std::filesystem::path entryFile(const std::filesystem::path& directory,
                                const std::string& model_file, uint64_t key) {
  return directory /
         fmt::format("{}-{:016x}.stocsmap", std::filesystem::path(model_file).stem().string(), key);
}

/// What is computed on loading rather than stored.
void findSymmetries(PreparedModel& m) {
  m.near_symmetries = findNearSymmetries(m.model);
  m.shape_alternatives = findShapeAlternatives(m.model);
  m.lathe = findLatheAxis(m.model, m.shape_alternatives);
}

PreparedModel prepareUncached(const std::string& model_file, float unit_scale,
                              const ModelPreparationParams& params) {
  return prepareMesh(loadMesh(model_file, unit_scale), params);
}

}  // namespace

const char* toString(CacheOutcome outcome) {
  switch (outcome) {
    case CacheOutcome::kLoaded:
      return "loaded from cache";
    case CacheOutcome::kBuilt:
      return "built and cached";
    case CacheOutcome::kRebuilt:
      return "rebuilt (invalid cache entry)";
    case CacheOutcome::kUncached:
      return "built (not cached)";
  }
  return "?";
}

PreparedModel prepareMesh(const MeshData& mesh, const ModelPreparationParams& params) {
  PreparedModel m;
  m.model = prepareModel(mesh, params.sampling);
  m.ppf_map = PpfHashMap::build(m.model, params.ppf);
  findSymmetries(m);
  return m;
}

PreparedModel prepareModelFile(const std::string& model_file, float unit_scale,
                               const ModelPreparationParams& params) {
  params.validate();
  return prepareUncached(model_file, unit_scale, params);
}

ModelCache::ModelCache(std::filesystem::path directory) : directory_(std::move(directory)) {}

std::filesystem::path ModelCache::defaultDirectory() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    return std::filesystem::path(xdg) / "stocs_ros";
  }
  if (const char* home = std::getenv("HOME"); home && *home) {
    return std::filesystem::path(home) / ".cache" / "stocs_ros";
  }
  return std::filesystem::temp_directory_path() / "stocs_ros-cache";
}

std::filesystem::path ModelCache::entryPath(const std::string& model_file, float unit_scale,
                                            const ModelPreparationParams& params) const {
  return entryFile(directory_, model_file,
                   entryKey(modelKeyBytes(model_file, unit_scale), unit_scale, params));
}

PreparedModel ModelCache::load(const std::string& model_file, float unit_scale,
                               const ModelPreparationParams& params, CacheReport* report) const {
  params.validate();
  CacheReport local;
  CacheReport& r = report ? *report : local;
  r = CacheReport{};
  if (directory_.empty()) return prepareUncached(model_file, unit_scale, params);

  std::error_code ec;
  if (!std::filesystem::is_regular_file(model_file, ec)) {
    throw InputError(fmt::format("model {}: no such file", model_file));
  }
  const uint64_t key = entryKey(modelKeyBytes(model_file, unit_scale), unit_scale, params);
  r.entry = entryFile(directory_, model_file, key);
  bool existed = std::filesystem::exists(r.entry, ec);
  if (existed) {
    try {
      PreparedModel m = readEntry(r.entry, key);
      findSymmetries(m);
      r.outcome = CacheOutcome::kLoaded;
      return m;
    } catch (const InputError& e) {
      r.detail = fmt::format("cache entry {}: {}", r.entry.string(), e.what());
    }
  }
  PreparedModel m = prepareUncached(model_file, unit_scale, params);
  const std::string problem = writeEntry(r.entry, key, m);
  if (!problem.empty()) {
    r.outcome = CacheOutcome::kUncached;
    r.detail = r.detail.empty() ? problem : r.detail + "; " + problem;
  } else {
    r.outcome = existed ? CacheOutcome::kRebuilt : CacheOutcome::kBuilt;
  }
  return m;
}

}  // namespace stocs
