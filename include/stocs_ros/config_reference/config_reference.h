#pragma once
// The reference files written from the parameter schemas: config/default.yaml (every key of the
// node's configuration with its default) and docs/parameters.md. A test checks that the committed
// files match; scripts/update_config_reference.sh rewrites them.

#include <string>

namespace stocs_ros {

/// config/default.yaml: the example object, then every schema key with its default and meaning.
std::string defaultConfigYaml();

/// docs/parameters.md: the node's keys, then the estimation keys with their `stocs` options.
std::string parametersMarkdown();

}  // namespace stocs_ros
