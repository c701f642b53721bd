// `stocs synth`: generates a BOP dataset of cluttered tabletop scenes (synthetic_dataset.h).
#include <fmt/format.h>

#include "cli_options.h"
#include "commands.h"
#include "stocs/sim/synthetic_dataset.h"

namespace stocs::tools {
namespace {

struct SynthOptions {
  std::string out;
  std::string models;
  SyntheticDatasetParams params;
  bool quiet = false;
};

int runSynth(const SynthOptions& o) {
  validateSchemaOptions(SyntheticDatasetParams::schema(), o.params);
  double seconds = 0;
  int images = 0;
  writeSyntheticDataset(o.out, o.params, o.models, [&](const SyntheticImageReport& r) {
    seconds += r.seconds;
    ++images;
    if (!o.quiet) {
      fmt::print(stderr, "scene {} image {}: {} objects, {:.3f} s\n", r.scene_id, r.im_id,
                 r.objects, r.seconds);
    }
  });
  fmt::print(stderr, "{} images in {}; {:.3f} s per image\n", images, o.out, seconds / images);
  return 0;
}

}  // namespace

Command registerSynth(CLI::App& app) {
  auto o = std::make_shared<SynthOptions>();
  SyntheticDatasetParams& p = o->params;
  CLI::App* cmd = app.add_subcommand(
      "synth",
      "Generate a BOP dataset of cluttered tabletop scenes with sensor-like depth and "
      "simulated probability maps");
  cmd->add_option("--out", o->out, "Output folder (must not exist or be empty)")->required();
  cmd->add_option("--models", o->models,
                  "BOP models folder to copy (obj_*.ply meshes with faces in mm, "
                  "models_info.json; a point model is refused); default: the project's own meshes");
  addSchemaOptions(*cmd, SyntheticDatasetParams::schema(), p);
  // A bare `--sequence` switches sequences on: a flag rather than the schema's `--sequence BOOL`.
  CLI::Option* sequence = cmd->get_option("--sequence");
  const std::string sequence_help = sequence->get_description();
  cmd->remove_option(sequence);
  cmd->add_flag("--sequence", p.sequence.enabled, sequence_help)->group("Sequences");
  cmd->add_option("--width", p.camera.width, "Image width, pixels");
  cmd->add_option("--height", p.camera.height, "Image height, pixels");
  cmd->add_option("--fx", p.camera.fx, "Focal length x, pixels");
  cmd->add_option("--fy", p.camera.fy, "Focal length y, pixels");
  cmd->add_option("--cx", p.camera.cx, "Principal point x, pixels");
  cmd->add_option("--cy", p.camera.cy, "Principal point y, pixels");
  cmd->add_flag("--quiet", o->quiet, "Print only the summary");
  return {cmd, [o] { return runSynth(*o); }};
}

}  // namespace stocs::tools
