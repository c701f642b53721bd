#include "cli_options.h"

#include <fmt/format.h>

#include <type_traits>
#include <variant>

namespace stocs::tools {

ModelCache ModelOptions::cache() const {
  return ModelCache(no_cache ? std::filesystem::path() : std::filesystem::path(cache_dir));
}

void addParamOption(CLI::App& cmd, const ParamInfo& info, const ParamRef& field) {
  const std::string help =
      info.unit.empty() ? info.meaning : fmt::format("{} ({})", info.meaning, info.unit);
  CLI::Option* option = std::visit(
      [&](auto f) -> CLI::Option* {
        using Field = decltype(f);
        if constexpr (std::is_same_v<Field, ChoiceRef> ||
                      std::is_same_v<Field, std::vector<std::string>*> ||
                      std::is_same_v<Field, std::vector<int>*>) {
          return nullptr;  // the core has no choice or list parameters
        } else {
          return cmd.add_option(info.cliFlag(), *f, help);
        }
      },
      field);
  if (option && !info.group.empty()) option->group(info.group);
}

void addSelectionOptions(CLI::App& cmd, std::string& split, std::vector<int>& scenes,
                         std::vector<int>& objects) {
  cmd.add_option("--split", split, "Dataset split folder");
  cmd.add_option("--scenes", scenes, "Scene ids, comma-separated (default: all)")->delimiter(',');
  cmd.add_option("--objects", objects, "Object ids, comma-separated (default: all)")
      ->delimiter(',');
}

void addModelOptions(CLI::App& cmd, ModelOptions& options) {
  if (options.cache_dir.empty()) options.cache_dir = ModelCache::defaultDirectory().string();
  cmd.add_option("--model-scale", options.unit_scale, "Model units to metres (BOP: mm, 0.001)");
  cmd.add_option("--cache-dir", options.cache_dir, "Folder for preprocessed model maps");
  cmd.add_flag("--no-cache", options.no_cache, "Neither read nor write the model cache");
}

}  // namespace stocs::tools
