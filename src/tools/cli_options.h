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

/// Adds an option for every estimation parameter (PipelineParams::schema()), writing into `params`.
void addPipelineOptions(CLI::App& cmd, PipelineParams& params);

/// Throws InputError naming the option ("--bases 0 is outside [1, 1000000]") of the first
/// estimation parameter out of range.
void validatePipelineOptions(const PipelineParams& params);

/// Adds --split, --scenes and --objects: which images and objects of a dataset to use.
void addSelectionOptions(CLI::App& cmd, std::string& split, std::vector<int>& scenes,
                         std::vector<int>& objects);

/// Adds --model-scale, --cache-dir and --no-cache.
void addModelOptions(CLI::App& cmd, ModelOptions& options);

}  // namespace stocs::tools
