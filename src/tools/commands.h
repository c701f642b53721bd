#pragma once
// Subcommands of the `stocs` tool. Each registers its options on the app and returns the subcommand
// with the function that runs it after parsing (exit code; InputError propagates to main).

#include <CLI/CLI.hpp>
#include <functional>

namespace stocs::tools {

struct Command {
  CLI::App* app;
  std::function<int()> run;
};

Command registerEstimate(CLI::App& app);
Command registerEval(CLI::App& app);
Command registerBench(CLI::App& app);
Command registerPrepare(CLI::App& app);
Command registerOverlay(CLI::App& app);
Command registerSimstats(CLI::App& app);
Command registerMeshes(CLI::App& app);
Command registerSynth(CLI::App& app);
Command registerCalibrate(CLI::App& app);
Command registerSimmaps(CLI::App& app);
Command registerColourModels(CLI::App& app);

}  // namespace stocs::tools
