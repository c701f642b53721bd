#pragma once
// Command-line options shared by the subcommands of `stocs`: every estimation parameter, with its
// default shown by --help.

#include <CLI/CLI.hpp>
#include <string>

#include "stocs/pipeline.h"

namespace stocs::tools {

struct ModelOptions {
  float unit_scale = 0.001f;  ///< BOP models are in mm
  std::string cache_dir;
  bool no_cache = false;

  /// The cache the options select (disabled with --no-cache).
  ModelCache cache() const;
};

/// Adds the options of every estimation stage, writing into `params`.
void addPipelineOptions(CLI::App& cmd, PipelineParams& params);

/// Adds --model-scale, --cache-dir and --no-cache.
void addModelOptions(CLI::App& cmd, ModelOptions& options);

}  // namespace stocs::tools
