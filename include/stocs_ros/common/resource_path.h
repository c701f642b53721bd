#pragma once
// Paths written in configuration files: `$(env VAR)` expands as in roslaunch, `$(dataset)` to the
// dataset folder the node was given (its ~dataset parameter, which the launch files set from their
// `dataset` argument), `package://PKG/REL` names a file of a ROS package, `file://` is stripped,
// and relative paths are relative to the configuration file's folder.

#include <filesystem>
#include <string>

namespace stocs_ros {

/// What the paths of one configuration file resolve against.
struct PathContext {
  std::filesystem::path base_dir;  ///< the configuration file's folder
  std::filesystem::path dataset;   ///< what $(dataset) stands for; empty: no dataset given
};

/// The file `text` names. Throws stocs::InputError for an unset variable, $(dataset) without a
/// dataset, or an unknown package.
std::filesystem::path resolveResourcePath(const std::string& text, const PathContext& context);

/// A URL rviz can load (a mesh_resource): package:// URLs stay as they are (after $(env) and
/// $(dataset) expansion), anything else becomes file:// and an absolute path.
std::string resourceUrl(const std::string& text, const PathContext& context);

}  // namespace stocs_ros
