// `stocs`: 6D object pose estimation with Stochastic Congruent Sets on BOP-format datasets.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <vector>

#include "commands.h"
#include "stocs/util/error.h"
#include "stocs/util/openmp_wait.h"
#ifdef STOCS_HAVE_OPEN3D
#include "stocs/methods/open3d_methods.h"
#endif

int main(int argc, char** argv) {
  stocs::preferPassiveOpenMpWaiting(argv);
#ifdef STOCS_HAVE_OPEN3D
  stocs::registerOpen3dMethods();  // before the options, whose help lists the methods
#endif
  CLI::App app{"stocs: 6D object pose estimation with Stochastic Congruent Sets (BMVC 2018)"};
  app.require_subcommand(1);
  app.option_defaults()->always_capture_default();
  const std::vector<stocs::tools::Command> commands = {
      stocs::tools::registerEstimate(app),    stocs::tools::registerPrepare(app),
      stocs::tools::registerEval(app),        stocs::tools::registerBench(app),
      stocs::tools::registerOverlay(app),     stocs::tools::registerSimstats(app),
      stocs::tools::registerMeshes(app),      stocs::tools::registerSynth(app),
      stocs::tools::registerCalibrate(app),   stocs::tools::registerSimmaps(app),
      stocs::tools::registerColourModels(app)};
  CLI11_PARSE(app, argc, argv);
  try {
    for (const stocs::tools::Command& command : commands) {
      if (command.app->parsed()) return command.run();
    }
  } catch (const stocs::InputError& e) {
    fmt::print(stderr, "stocs: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "stocs: internal error: {}\n", e.what());
    return 3;
  }
  return 1;
}
