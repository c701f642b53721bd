#pragma once
// The parameters of a schema written out for people: as a YAML file of defaults with a comment per
// key (config/default.yaml) and as a markdown table (docs/parameters.md).

#include <string>
#include <utility>
#include <vector>

#include "stocs/util/param_set.h"

namespace stocs {

/// Parameters with their values as text, as ParamSet::describe() gives them.
using DescribedParams = std::vector<std::pair<ParamInfo, std::string>>;

/// `key: value  # meaning (unit, range)` lines, nested into maps by the dotted keys, each level
/// indented by two spaces more than `indent`.
std::string paramsYaml(const DescribedParams& params, int indent = 0);

/// A markdown table with a row per parameter: key (after `key_prefix`), default, unit, allowed
/// values, meaning, and with `cli_flags` the `stocs` option.
std::string paramsMarkdown(const DescribedParams& params, const std::string& key_prefix,
                           bool cli_flags);

}  // namespace stocs
