// `stocs synth`: generates a BOP dataset of cluttered tabletop scenes (synthetic_dataset.h).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "commands.h"
#include "stocs/sim/segmentation_simulator.h"
#include "stocs/sim/synthetic_dataset.h"

namespace stocs::tools {
namespace {

struct SynthOptions {
  std::string out;
  std::string models;
  SyntheticDatasetParams params;
  std::vector<float> distance{0.55f, 0.9f};
  std::vector<float> elevation{30, 75};
  bool quiet = false;
};

int runSynth(SynthOptions o) {
  o.params.layout.min_distance = o.distance.at(0);
  o.params.layout.max_distance = o.distance.at(1);
  o.params.layout.min_elevation_deg = o.elevation.at(0);
  o.params.layout.max_elevation_deg = o.elevation.at(1);
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
                  "BOP models folder to copy (obj_*.ply in mm, models_info.json); default: the "
                  "project's own meshes");
  cmd->add_option("--scenes", p.scenes, "Scenes (object arrangements)");
  cmd->add_option("--images", p.images_per_scene, "Views per scene");
  cmd->add_option("--objects", p.layout.objects, "Dataset objects per scene");
  cmd->add_option("--distractors", p.layout.distractors, "Shapes without ground truth per scene");
  cmd->add_option("--table-radius", p.layout.table_radius,
                  "Object centres lie within this radius of the table centre, m");
  cmd->add_option("--distance", o->distance, "Camera distance range to the table centre, m")
      ->expected(2)
      ->delimiter(',');
  cmd->add_option("--elevation", o->elevation, "Camera elevation range above the table, degrees")
      ->expected(2)
      ->delimiter(',');
  cmd->add_option("--width", p.camera.width, "Image width, pixels");
  cmd->add_option("--height", p.camera.height, "Image height, pixels");
  cmd->add_option("--fx", p.camera.fx, "Focal length x, pixels");
  cmd->add_option("--fy", p.camera.fy, "Focal length y, pixels");
  cmd->add_option("--cx", p.camera.cx, "Principal point x, pixels");
  cmd->add_option("--cy", p.camera.cy, "Principal point y, pixels");
  cmd->add_option("--depth-noise", p.depth_noise_level,
                  "Depth sensor noise level: 0 exact, 1 a Kinect-like sensor, higher is noisier");
  cmd->add_option("--depth-scale", p.depth_scale, "mm per unit of the written depth images");
  cmd->add_option("--segmentation", p.segmentation_preset,
                  "Segmentation simulator preset of prob/: " +
                      fmt::format("{}", fmt::join(segmentationPresetNames(), ", ")));
  cmd->add_option("--absent", p.absent_per_image,
                  "Objects per image that are not in the scene but get a probability map (the "
                  "simulator's confusion or noise) and a target with inst_count 0 in "
                  "test_targets_bop19.json; fewer when the models run out");
  cmd->add_option("--seed", p.seed, "Random seed: the same seed writes the same files");
  cmd->add_flag("--quiet", o->quiet, "Print only the summary");
  return {cmd, [o] { return runSynth(*o); }};
}

}  // namespace stocs::tools
