#pragma once
// Paths written in configuration files: `$(env VAR)` expands as in roslaunch, `package://PKG/REL`
// names a file of a ROS package, `file://` is stripped, and relative paths are relative to the
// configuration file's folder.

#include <filesystem>
#include <string>

namespace stocs_ros {

/// The file `text` names. Throws stocs::InputError for an unset variable or an unknown package.
std::filesystem::path resolveResourcePath(const std::string& text,
                                          const std::filesystem::path& base_dir);

/// A URL rviz can load (a mesh_resource): package:// URLs stay as they are (after $(env)
/// expansion), anything else becomes file:// and an absolute path.
std::string resourceUrl(const std::string& text, const std::filesystem::path& base_dir);

}  // namespace stocs_ros
