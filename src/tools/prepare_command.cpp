// `stocs prepare`: preprocess (and cache) object models, printing what was built.
#include <fmt/format.h>

#include <chrono>

#include "cli_options.h"
#include "commands.h"
#include "stocs/util/error.h"

namespace stocs::tools {
namespace {

struct PrepareOptions {
  std::vector<std::string> models;
  PipelineParams params;
  ModelOptions model;
};

int runPrepare(const PrepareOptions& o) {
  validatePipelineOptions(o.params);
  const ModelCache cache = o.model.cache();
  for (const std::string& file : o.models) {
    const auto start = std::chrono::steady_clock::now();
    CacheReport report;
    const PreparedModel m = cache.load(file, o.model.unit_scale, o.params.model, &report);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    fmt::print(
        "{}: diameter {:.1f} mm, {} samples (radius {:.2f} mm), {} stored pairs in {} bins, "
        "{:.2f} MB, {} in {:.3f} s{}\n",
        file, m.model.diameter * 1000, m.model.size(), m.model.sampling_radius * 1000,
        m.ppf_map.pairCount(), m.ppf_map.occupiedKeyCount(), m.ppf_map.memoryBytes() / 1e6,
        toString(report.outcome), seconds,
        report.entry.empty() ? "" : " -> " + report.entry.string());
    if (!report.detail.empty()) fmt::print("  note: {}\n", report.detail);
  }
  return 0;
}

}  // namespace

Command registerPrepare(CLI::App& app) {
  auto o = std::make_shared<PrepareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "prepare", "Preprocess object models (samples, normals, PPF map) into the cache");
  cmd->add_option("models", o->models, "Model files (PLY, PCD, OBJ, STL, DAE, glTF, GLB)")
      ->required();
  addModelOptions(*cmd, o->model);
  addPipelineOptions(*cmd, o->params);
  return {cmd, [o] { return runPrepare(*o); }};
}

}  // namespace stocs::tools
