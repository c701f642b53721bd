// Prints config/default.yaml (--yaml) or docs/parameters.md (--markdown) as the parameter schemas
// give them (scripts/update_config_reference.sh).
#include <cstring>
#include <iostream>

#include "stocs_ros/config_reference/config_reference.h"

int main(int argc, char** argv) {
  if (argc == 2 && std::strcmp(argv[1], "--yaml") == 0) {
    std::cout << stocs_ros::defaultConfigYaml();
  } else if (argc == 2 && std::strcmp(argv[1], "--markdown") == 0) {
    std::cout << stocs_ros::parametersMarkdown();
  } else {
    std::cerr << "usage: config_reference --yaml | --markdown\n";
    return 2;
  }
  return 0;
}
