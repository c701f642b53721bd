// `stocs simmaps`: a real dataset without network maps (ycbv-0000) made playable as a short
// sequence with simulated maps, targets and frame times, in a new folder (simulated_maps.h).
#include <fmt/format.h>

#include "commands.h"
#include "stocs/sim/segmentation_simulator.h"
#include "stocs/sim/simulated_maps.h"

namespace stocs::tools {

Command registerSimmaps(CLI::App& app) {
  struct Options {
    std::string dataset, out;
    SimulatedMapsParams params;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "simmaps",
      "Make a BOP dataset without network maps playable as a sequence: a new folder linking to its "
      "models and images, with simulated maps in prob/, test_targets_bop19.json and "
      "scene_events.json");
  cmd->add_option("--dataset", o->dataset, "BOP dataset to read (only read)")->required();
  cmd->add_option("--out", o->out, "Output folder (must not exist or be empty)")->required();
  cmd->add_option(
      "--segmentation", o->params.segmentation_preset,
      fmt::format("Segmentation simulator preset: {}", fmt::join(segmentationPresetNames(), ", ")));
  cmd->add_option("--absent", o->params.absent_per_image,
                  "Objects of models/ per scene that are not in it, listed with inst_count 0 and "
                  "given a map");
  cmd->add_option("--rate", o->params.rate_hz,
                  "Frame rate of the sequence the images form, in image id order (Hz)");
  cmd->add_option("--seed", o->params.seed, "Random seed: the same seed writes the same maps");
  return {cmd, [o] {
            writeSimulatedMapsDataset(o->dataset, o->out, o->params);
            fmt::print(stderr, "{}: simulated maps and targets of {}\n", o->out, o->dataset);
            return 0;
          }};
}

}  // namespace stocs::tools
