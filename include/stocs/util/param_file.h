#pragma once
// A parameter struct read from a flat YAML file through its ParamSet schema (the format of the
// ROS nodes' private parameter files, e.g. config/segmenter.yaml), for the tools that take such a
// file without ROS.

#include <filesystem>
#include <vector>

#include "stocs/util/param_set.h"

namespace stocs {

/// One field of the struct being read and what the schema says of it.
struct ParamField {
  ParamInfo info;
  ParamRef field;
};

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
