#include "model_file_check.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>
#include <vector>

#include "stocs/util/error.h"

namespace stocs::detail {

InputError modelError(const std::string& path, const std::string& why) {
  return InputError(fmt::format("model {}: {}", path, why));
}

namespace {

constexpr size_t kMaxHeaderLines = 1000;
constexpr uint64_t kMaxElements = 100'000'000;  // far above any graspable object's model

/// The header lines of a model file (up to and including the line starting with `last`) and the
/// number of bytes after them. With `magic`, the first line must be that word.
struct Header {
  std::vector<std::vector<std::string>> lines;  // each line split at white space
  std::vector<std::string> raw_lines;
  uint64_t body_bytes = 0;
  std::string body_start;  // the body's first bytes, up to kBodyStart
};

constexpr size_t kBodyStart = 4096;

Header readHeader(const std::string& path, const std::string& last, const std::string& magic = "") {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("model {}: cannot open for reading", path));
  Header h;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (std::any_of(line.begin(), line.end(),
                    [](unsigned char c) { return c < 0x20 && c != '\t'; })) {
      throw InputError(
          fmt::format("model {}: header line {} is not text", path, h.lines.size() + 1));
    }
    h.raw_lines.push_back(line);
    std::istringstream words(line);
    h.lines.emplace_back(std::istream_iterator<std::string>(words),
                         std::istream_iterator<std::string>());
    if (!magic.empty() && h.lines.size() == 1 && h.lines[0] != std::vector<std::string>{magic}) {
      std::string format = magic;  // "ply" -> "PLY"
      std::transform(format.begin(), format.end(), format.begin(),
                     [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
      throw InputError(
          fmt::format("model {}: not a {} file (its first line is not '{}')", path, format, magic));
    }
    if (!h.lines.back().empty() && h.lines.back()[0] == last) {
      const std::streamoff header_end = in.tellg();
      h.body_start.resize(kBodyStart);
      in.read(h.body_start.data(), kBodyStart);
      h.body_start.resize(static_cast<size_t>(in.gcount()));
      in.clear();
      in.seekg(0, std::ios::end);
      h.body_bytes = header_end < 0 ? 0 : static_cast<uint64_t>(in.tellg() - header_end);
      return h;
    }
    if (h.lines.size() >= kMaxHeaderLines) break;
  }
  throw InputError(fmt::format("model {}: header has no '{}' line", path, last));
}

/// A non-negative decimal count of at most `max`, or an InputError.
uint64_t parseCount(const std::string& path, const std::string& what, const std::string& text,
                    uint64_t max) {
  if (text.empty() || text.size() > 12 ||
      text.find_first_not_of("0123456789") != std::string::npos || std::stoull(text) > max) {
    throw InputError(
        fmt::format("model {}: {} '{}' is not a count up to {}", path, what, text, max));
  }
  return std::stoull(text);
}

/// Bytes of a PLY scalar type; 0 when unknown.
size_t plyTypeSize(const std::string& type) {
  static const std::map<std::string, size_t> sizes = {
      {"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},  {"short", 2}, {"ushort", 2},
      {"int16", 2}, {"uint16", 2},  {"int", 4},    {"uint", 4},   {"int32", 4}, {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto it = sizes.find(type);
  return it == sizes.end() ? 0 : it->second;
}

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<std::vector<std::string>> properties;  // the words after `property`
};

/// The values of a PCD header's keywords (the words after each), every keyword a known one given
/// once, and those PCL needs present.
class PcdKeywords {
 public:
  PcdKeywords(const std::string& path, const Header& h) {
    for (size_t i = 0; i < h.lines.size(); ++i) {
      // PCL's reader dereferences null for binary data behind blank or indented header lines
      // (found by fuzz_pcd_model).
      const std::string& raw = h.raw_lines[i];
      if (raw.empty() || raw[0] == ' ' || raw[0] == '\t') {
        throw modelError(path, fmt::format("PCD header line {} is blank or indented", i + 1));
      }
      const std::vector<std::string>& w = h.lines[i];
      if (w[0][0] == '#') continue;
      static const char* const kKeywords[] = {"VERSION", "FIELDS", "SIZE",      "TYPE",   "COUNT",
                                              "WIDTH",   "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};
      if (std::find(std::begin(kKeywords), std::end(kKeywords), w[0]) == std::end(kKeywords)) {
        throw modelError(path, fmt::format("unknown PCD header keyword '{}'", w[0]));
      }
      if (!values_.emplace(w[0], std::vector<std::string>(w.begin() + 1, w.end())).second) {
        throw modelError(path, fmt::format("PCD header repeats '{}'", w[0]));
      }
    }
    for (const char* required : {"FIELDS", "SIZE", "TYPE", "WIDTH", "HEIGHT", "POINTS"}) {
      if (!values_.count(required)) {
        throw modelError(path, fmt::format("PCD header lacks '{}'", required));
      }
    }
  }

  /// The words after `keyword`; none when the header lacks it.
  const std::vector<std::string>& operator[](const std::string& keyword) const {
    static const std::vector<std::string> kNone;
    const auto it = values_.find(keyword);
    return it == values_.end() ? kNone : it->second;
  }

 private:
  std::map<std::string, std::vector<std::string>> values_;
};

/// Bytes of one binary point: FIELDS, SIZE, TYPE and COUNT (1 each when absent) of one length,
/// each field of a PCD size and type with a COUNT of at least 1.
uint64_t pcdPointBytes(const std::string& path, const PcdKeywords& values) {
  const std::vector<std::string>& names = values["FIELDS"];
  const std::vector<std::string>& sizes = values["SIZE"];
  const std::vector<std::string>& types = values["TYPE"];
  const size_t fields = names.size();
  std::vector<std::string> counts = values["COUNT"];
  if (counts.empty()) counts.assign(fields, "1");
  if (fields == 0 || sizes.size() != fields || types.size() != fields || counts.size() != fields) {
    throw modelError(path, "PCD FIELDS, SIZE, TYPE and COUNT differ in length");
  }
  uint64_t point_bytes = 0;
  for (size_t f = 0; f < fields; ++f) {
    const std::string& size = sizes[f];
    const std::string& type = types[f];
    const bool valid_size = size == "1" || size == "2" || size == "4" || size == "8";
    if (!valid_size || (type != "I" && type != "U" && type != "F") ||
        (type == "F" && size != "4" && size != "8")) {
      throw modelError(path,
                       fmt::format("PCD field '{}' has size {} and type {}", names[f], size, type));
    }
    // COUNT 0 makes PCL compute a negative field size (found by fuzz_pcd_model).
    const uint64_t count = parseCount(path, "PCD COUNT", counts[f], 1 << 20);
    if (count == 0) throw modelError(path, fmt::format("PCD field '{}' has COUNT 0", names[f]));
    point_bytes += std::stoull(size) * count;
  }
  return point_bytes;
}

/// The count after `keyword` (POINTS, WIDTH or HEIGHT), which must be a single number.
uint64_t pcdNumber(const std::string& path, const PcdKeywords& values, const char* keyword) {
  const std::vector<std::string>& words = values[keyword];
  if (words.size() != 1) throw modelError(path, fmt::format("PCD {} must be one number", keyword));
  return parseCount(path, fmt::format("PCD {}", keyword), words[0], kMaxElements);
}

/// The fewest body bytes that hold `points` points of DATA `kind`.
uint64_t pcdBodyBytes(const std::string& path, const std::string& kind, uint64_t points,
                      size_t fields, uint64_t point_bytes) {
  if (kind == "ascii") return points * fields * 2 - 1;  // a digit and a separator per value
  if (kind == "binary") return points * point_bytes;
  // binary_compressed: the compressed and uncompressed sizes; PCL checks the rest.
  if (kind == "binary_compressed") return 8;
  throw modelError(path, "PCD DATA must be ascii, binary or binary_compressed");
}

/// Rejects a body whose first line PCL would take for more header.
void checkPcdBodyStart(const std::string& path, const std::string& kind,
                       const std::string& body_start) {
  // PCL's header parser goes on reading lines after DATA while they start with a header keyword,
  // so data that happens to begin like one (after empty lines, which it skips) is parsed as
  // header and crashes it: binary data, and ascii data such as a second "DATA" line without a
  // kind (both found by fuzz_pcd_model).
  std::istringstream body(body_start);
  std::string line;
  while (std::getline(body, line) && line.empty()) {
  }
  std::istringstream words(line);
  std::string first;
  words >> first;
  static const char* const kPrefixes[] = {"#",      "VERSION", "FIELDS",    "COLUMNS",
                                          "SIZE",   "TYPE",    "COUNT",     "WIDTH",
                                          "HEIGHT", "POINTS",  "VIEWPOINT", "DATA"};
  for (const char* prefix : kPrefixes) {
    if (first.rfind(prefix, 0) == 0) {
      throw modelError(path,
                       fmt::format("PCD {} data begins like the header line '{}'", kind, prefix));
    }
  }
}
}  // namespace

void checkPlyHeader(const std::string& path) {
  const Header h = readHeader(path, "end_header", "ply");
  std::string format;
  std::vector<PlyElement> elements;
  for (size_t i = 1; i + 1 < h.lines.size(); ++i) {
    const std::vector<std::string>& w = h.lines[i];
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "format" && w.size() == 3 && format.empty() && w[2] == "1.0" &&
        (w[1] == "ascii" || w[1] == "binary_little_endian" || w[1] == "binary_big_endian")) {
      format = w[1];
    } else if (w[0] == "element" && w.size() == 3) {
      elements.push_back({w[1], parseCount(path, "element count", w[2], kMaxElements), {}});
    } else if (w[0] == "property" && !elements.empty()) {
      elements.back().properties.emplace_back(w.begin() + 1, w.end());
    } else {
      throw modelError(path, fmt::format("header line {} ('{}') is not valid here", i + 1, w[0]));
    }
  }
  if (format.empty()) throw modelError(path, "header has no valid 'format' line");
  if (elements.empty() || elements[0].name != "vertex")
    throw modelError(path, "first element is not 'vertex'");
  if (elements[0].count == 0) throw modelError(path, "no vertices");
  if (elements.size() > 2 || (elements.size() == 2 && elements[1].name != "face")) {
    throw modelError(path, "only 'vertex' and 'face' elements are supported");
  }
  if (elements[0].properties.empty()) throw modelError(path, "vertices have no properties");
  size_t vertex_bytes = 0;
  for (const auto& p : elements[0].properties) {
    if (p.size() != 2 || plyTypeSize(p[0]) == 0) {
      throw modelError(path, "vertex properties must be single values of a PLY scalar type");
    }
    vertex_bytes += plyTypeSize(p[0]);
  }
  uint64_t face_min_bytes = 0;
  // PCL's own writer declares an empty 'element face 0' without properties for point clouds.
  const bool empty_faces =
      elements.size() == 2 && elements[1].count == 0 && elements[1].properties.empty();
  if (elements.size() == 2 && !empty_faces) {
    const auto& p = elements[1].properties;
    if (p.size() != 1 || p[0].size() != 4 || p[0][0] != "list" ||
        (p[0][1] != "uchar" && p[0][1] != "uint8") ||
        (p[0][2] != "int" && p[0][2] != "uint" && p[0][2] != "int32" && p[0][2] != "uint32") ||
        (p[0][3] != "vertex_indices" && p[0][3] != "vertex_index")) {
      throw modelError(path, "faces must have one property 'list uchar int vertex_indices'");
    }
    face_min_bytes = elements[1].count;  // the count byte of each face
  }
  // Each ascii value takes at least a digit and a separator.
  const uint64_t needed = format == "ascii"
                              ? elements[0].count * elements[0].properties.size() * 2 - 1
                              : elements[0].count * vertex_bytes + face_min_bytes;
  if (h.body_bytes < needed) {
    throw modelError(path,
                     fmt::format("{} vertices need at least {} bytes of data, the file has {}",
                                 elements[0].count, needed, h.body_bytes));
  }
}

void checkPcdHeader(const std::string& path) {
  const Header h = readHeader(path, "DATA");
  const PcdKeywords values(path, h);
  const uint64_t point_bytes = pcdPointBytes(path, values);
  const uint64_t points = pcdNumber(path, values, "POINTS");
  if (points == 0) throw modelError(path, "no vertices");
  if (pcdNumber(path, values, "WIDTH") * pcdNumber(path, values, "HEIGHT") != points) {
    throw modelError(path, "PCD WIDTH x HEIGHT is not POINTS");
  }
  const std::vector<std::string>& data = values["DATA"];
  const std::string kind = data.size() == 1 ? data[0] : "";
  const uint64_t needed = pcdBodyBytes(path, kind, points, values["FIELDS"].size(), point_bytes);
  if (h.body_bytes < needed) {
    throw modelError(path, fmt::format("{} points need at least {} bytes of data, the file has {}",
                                       points, needed, h.body_bytes));
  }
  checkPcdBodyStart(path, kind, h.body_start);
}

void checkGlbChunks(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const auto word = [&]() {  // little-endian uint32, or none at the end of the file
    unsigned char b[4];
    if (!in.read(reinterpret_cast<char*>(b), 4)) return std::optional<uint32_t>();
    return std::optional<uint32_t>(b[0] | b[1] << 8 | b[2] << 16 |
                                   static_cast<uint32_t>(b[3]) << 24);
  };
  const auto magic = word(), version = word(), length = word();
  if (!length || *magic != 0x46546C67u)
    throw modelError(path, "not a binary glTF (no glTF header)");
  if (*version != 2)
    throw modelError(path, fmt::format("binary glTF version {} (only 2 is read)", *version));
  const uint64_t size = std::filesystem::file_size(path);
  if (*length != size) {
    throw modelError(
        path, fmt::format("binary glTF header gives {} bytes, the file has {}", *length, size));
  }
  for (uint64_t offset = 12; offset < size;) {
    const auto chunk = word();
    if (!chunk || !word() || offset + 8 + *chunk > size) {
      throw modelError(
          path, fmt::format("binary glTF chunk at byte {} runs past the file's end", offset));
    }
    in.seekg(static_cast<std::streamoff>(*chunk), std::ios::cur);
    offset += 8 + *chunk;
  }
}

}  // namespace stocs::detail
