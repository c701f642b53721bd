#include "stocs_ros/common/resource_path.h"

#include <fmt/format.h>
#include <ros/package.h>

#include <cstdlib>

#include "stocs/util/error.h"

namespace stocs_ros {
namespace {

constexpr char kPackageScheme[] = "package://";
constexpr char kFileScheme[] = "file://";
constexpr char kDatasetVariable[] = "$(dataset)";

bool startsWith(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

std::string expandEnv(const std::string& text) {
  std::string out;
  size_t pos = 0;
  while (true) {
    const size_t open = text.find("$(env ", pos);
    if (open == std::string::npos) break;
    const size_t close = text.find(')', open);
    if (close == std::string::npos) {
      throw stocs::InputError(fmt::format("path '{}': '$(env' without a closing ')'", text));
    }
    const std::string name = text.substr(open + 6, close - open - 6);
    const char* value = std::getenv(name.c_str());
    if (!value) {
      throw stocs::InputError(
          fmt::format("path '{}': environment variable {} is not set", text, name));
    }
    out += text.substr(pos, open - pos) + value;
    pos = close + 1;
  }
  return out + text.substr(pos);
}

/// `text` with $(env VAR) and $(dataset) expanded.
std::string expand(const std::string& text, const std::filesystem::path& dataset) {
  std::string out = expandEnv(text);
  const std::string variable = kDatasetVariable;
  for (size_t at = out.find(variable); at != std::string::npos;
       at = out.find(variable, at + dataset.native().size())) {
    if (dataset.empty()) {
      throw stocs::InputError(
          fmt::format("path '{}' uses $(dataset), but no dataset was given: set the node's "
                      "~dataset parameter (launch argument dataset:=FOLDER)",
                      text));
    }
    out.replace(at, variable.size(), dataset.native());
  }
  return out;
}

}  // namespace

std::filesystem::path resolveResourcePath(const std::string& text, const PathContext& context) {
  const std::string expanded = expand(text, context.dataset);
  if (startsWith(expanded, kPackageScheme)) {
    const std::string rest = expanded.substr(sizeof(kPackageScheme) - 1);
    const size_t slash = rest.find('/');
    if (slash == std::string::npos || slash + 1 == rest.size()) {
      throw stocs::InputError(fmt::format("path '{}' names a package but no file in it", text));
    }
    const std::string package = rest.substr(0, slash);
    const std::string package_dir = ros::package::getPath(package);
    if (package_dir.empty()) {
      throw stocs::InputError(
          fmt::format("path '{}': ROS package '{}' is not found", text, package));
    }
    return std::filesystem::path(package_dir) / rest.substr(slash + 1);
  }
  std::filesystem::path path =
      startsWith(expanded, kFileScheme) ? expanded.substr(sizeof(kFileScheme) - 1) : expanded;
  return path.is_absolute() ? path : std::filesystem::absolute(context.base_dir / path);
}

std::string resourceUrl(const std::string& text, const PathContext& context) {
  const std::string expanded = expand(text, context.dataset);
  if (startsWith(expanded, kPackageScheme)) return expanded;
  return kFileScheme + resolveResourcePath(expanded, context).lexically_normal().string();
}

}  // namespace stocs_ros
