#pragma once
// Command-line options shared by the subcommands of `stocs`: every estimation parameter, with its
// default shown by --help.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "stocs/estimation/pipeline.h"

namespace stocs::tools {

struct ModelOptions {
  float unit_scale = 0.001f;  ///< BOP models are in mm
  std::string cache_dir;
  bool no_cache = false;

  /// The cache the options select (disabled with --no-cache).
  ModelCache cache() const;
};

/// Adds the option of one parameter (ParamInfo::cliFlag, its meaning and unit as help), writing
/// into `field`; none for list and choice parameters.
void addParamOption(CLI::App& cmd, const ParamInfo& info, const ParamRef& field);

/// Adds an option for every parameter of `schema`, writing into `s`.
template <class S>
void addSchemaOptions(CLI::App& cmd, const ParamSet<S>& schema, S& s) {
  for (const auto& entry : schema.entries()) addParamOption(cmd, entry.info, entry.field(s));
}

/// Throws InputError naming the option ("--bases 0 is outside [1, 1000000]") of the first
/// parameter of `schema` out of range in `s`.
template <class S>
void validateSchemaOptions(const ParamSet<S>& schema, const S& s) {
  schema.validate(s, [](const ParamInfo& info) { return info.cliFlag(); });
}

/// Adds an option for every estimation parameter (PipelineParams::schema()), writing into `params`.
inline void addPipelineOptions(CLI::App& cmd, PipelineParams& params) {
  addSchemaOptions(cmd, PipelineParams::schema(), params);
}

/// Throws InputError naming the option of the first estimation parameter out of range.
inline void validatePipelineOptions(const PipelineParams& params) {
  validateSchemaOptions(PipelineParams::schema(), params);
}

/// Adds --split, --scenes and --objects: which images and objects of a dataset to use.
void addSelectionOptions(CLI::App& cmd, std::string& split, std::vector<int>& scenes,
                         std::vector<int>& objects);

/// Adds --model-scale, --cache-dir and --no-cache.
void addModelOptions(CLI::App& cmd, ModelOptions& options);

}  // namespace stocs::tools
