// config/default.yaml and docs/parameters.md are what the parameter schemas give: a parameter added
// to a schema without regenerating them (scripts/update_config_reference.sh) fails here.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "stocs_ros/config_reference/config_reference.h"

namespace stocs_ros {
namespace {

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(ConfigReference, CommittedFilesMatchTheSchemas) {
  EXPECT_EQ(readFile("config/default.yaml"), defaultConfigYaml())
      << "config/default.yaml is stale: run scripts/update_config_reference.sh";
  EXPECT_EQ(readFile("docs/parameters.md"), parametersMarkdown())
      << "docs/parameters.md is stale: run scripts/update_config_reference.sh";
}

}  // namespace
}  // namespace stocs_ros
