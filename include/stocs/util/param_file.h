#pragma once
// Parameters read from YAML through their ParamSet schema: a flat file for the tools that take a
// ROS node's private parameter file without ROS (e.g. config/segmenter.yaml), and the conversion
// of one YAML value that the node's own configuration reader shares.

#include <filesystem>
#include <string>
#include <vector>

#include "stocs/util/param_set.h"

namespace YAML {
class Node;
}

namespace stocs {

/// One field of the struct being read and what the schema says of it.
struct ParamField {
  ParamInfo info;
  ParamRef field;
};

/// The YAML document in `file`; throws InputError "file: `unreadable`" when it cannot be read and
/// "file: invalid YAML: ..." when it does not parse.
YAML::Node loadYamlFile(const std::filesystem::path& file, const char* unreadable);

/// Throws InputError "file:line: key: problem", the line being `n`'s.
[[noreturn]] void failAtYamlNode(const std::filesystem::path& file, const YAML::Node& n,
                                 const std::string& key, const std::string& problem);

/// `n`'s scalar as T (bool, int, float, double, uint64_t or std::string); throws InputError naming
/// the file, the line and `key` for a list, a map or a value that is not a T.
template <class T>
T readYamlScalar(const std::filesystem::path& file, const YAML::Node& n, const std::string& key);

/// Sets `field` from `n` (a scalar of its type, a list of strings, or one of `info`'s choices) and
/// checks it against `info`'s range; throws InputError naming the file, the line and `key`.
void assignParamNode(const std::filesystem::path& file, const YAML::Node& n, const std::string& key,
                     const ParamInfo& info, const ParamRef& field);

/// Sets each field whose key the file's top-level map holds. Throws InputError naming the file,
/// the line and the key for an unreadable file, a key no field has, a value of the wrong type, an
/// unknown choice or a value out of range.
void readParamFields(const std::filesystem::path& file, const std::vector<ParamField>& fields);

/// `params` with every key of the flat YAML map in `file` set through `schema` (readParamFields).
template <class S>
void readParamFile(const std::filesystem::path& file, const ParamSet<S>& schema, S& params) {
  std::vector<ParamField> fields;
  for (const auto& entry : schema.entries()) fields.push_back({entry.info, entry.field(params)});
  readParamFields(file, fields);
}

}  // namespace stocs
