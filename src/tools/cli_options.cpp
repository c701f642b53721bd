#include "cli_options.h"

namespace stocs::tools {

ModelCache ModelOptions::cache() const {
  return ModelCache(no_cache ? std::filesystem::path() : std::filesystem::path(cache_dir));
}

void addPipelineOptions(CLI::App& cmd, PipelineParams& p) {
  const std::string seg = "Soft segment (paper eqs. 1-3)";
  cmd.add_option("--epsilon", p.segment.min_probability,
                 "Pixels with class probability above this join the segment")
      ->group(seg);
  cmd.add_option("--voxel", p.segment.voxel_size, "Segment voxel size, m (0: every pixel)")
      ->group(seg);
  cmd.add_option("--samples-per-voxel", p.segment.samples_per_voxel,
                 "Pixel samples across a voxel at the segment's far depth; sets the scan's pixel "
                 "stride (0: every pixel)")
      ->group(seg);
  cmd.add_option("--normal-radius", p.segment.normals.radius, "Scene normal radius, m")->group(seg);

  const std::string model = "Model preprocessing";
  cmd.add_option("--model-sampling", p.model.sampling.sampling_ratio,
                 "Poisson-disc radius of model samples, fraction of the diameter")
      ->group(model);
  cmd.add_option("--ppf-distance-step", p.model.ppf.distance_step, "PPF distance bin, m")
      ->group(model);
  cmd.add_option("--ppf-angle-step", p.model.ppf.angle_step_deg, "PPF angle bin, degrees")
      ->group(model);
  cmd.add_option("--ppf-min-distance", p.model.ppf.min_distance_ratio,
                 "Shortest stored model pair, fraction of the diameter")
      ->group(model);

  const std::string stocs = "StoCS (paper section 3)";
  cmd.add_option("--bases", p.stocs.bases, "Bases sampled per object (at most, with --consensus)")
      ->group(stocs);
  cmd.add_option("--draw-budget", p.stocs.base_draw_budget,
                 "Base draws per object: a base with nothing to verify is drawn again, up to "
                 "budget / bases draws in all (at most 1 draw per base: the paper)")
      ->group(stocs);
  cmd.add_option("--consensus", p.stocs.consensus_bases,
                 "Stop between blocks of 10 bases once this many best bases all put the object "
                 "in the same place, out of free space (0: run every base; single instance only)")
      ->group(stocs);
  cmd.add_option("--time-budget", p.stocs.time_budget,
                 "Seconds per object; 0: no limit (a budget makes results machine-dependent)")
      ->group(stocs);
  cmd.add_option("--seed", p.stocs.seed, "Random seed")->group(stocs);
  cmd.add_option("--threads", p.stocs.threads,
                 "Threads per object (0: all cores); results do not depend on it")
      ->group(stocs);
  cmd.add_option("--focused-bases", p.stocs.focused_bases,
                 "The first this many bases draw their points by pi_k^focus-exponent, the others "
                 "by pi_k (0: every base by pi_k, the paper)")
      ->group(stocs);
  cmd.add_option("--focus-exponent", p.stocs.base.focus_exponent,
                 "Power of pi_k in the draws of focused bases (1 to 16)")
      ->group(stocs);
  cmd.add_option("--wide-angle", p.stocs.base.wide_angle_deg,
                 "epsilon_1: minimum base angle at b1, degrees")
      ->group(stocs);
  cmd.add_option("--coplanarity", p.stocs.base.coplanarity,
                 "epsilon_2: maximum distance of b4 from the plane of b1 b2 b3, m")
      ->group(stocs);
  cmd.add_option("--congruence-tolerance", p.stocs.congruent.tolerance,
                 "Distance tolerance of congruent sets, m")
      ->group(stocs);
  cmd.add_option("--max-sets", p.stocs.congruent.max_sets, "Congruent sets kept per base")
      ->group(stocs);
  cmd.add_option("--fit-rms", p.stocs.max_fit_rms, "Largest RMS of a base-to-set rigid fit, m")
      ->group(stocs);
  cmd.add_option("--min-normal-agreement", p.stocs.min_normal_agreement,
                 "Base points (0-4) whose normal must agree with the model's within delta_n for "
                 "a fit to be scored")
      ->group(stocs);
  cmd.add_option("--finished-per-base", p.stocs.finished_per_base,
                 "Hypotheses of a base scored in full: those best on the first share of the model")
      ->group(stocs);
  cmd.add_option("--delta-s", p.stocs.lcp.distance, "delta_s: LCP distance threshold, m")
      ->group(stocs);
  cmd.add_option("--delta-n", p.stocs.lcp.normal_angle_deg, "delta_n: LCP normal angle, degrees")
      ->group(stocs);
  cmd.add_option("--coarse-fraction", p.stocs.lcp.coarse_fraction,
                 "Share of the model scored first (the head), and again between coarse checks; "
                 "0: no coarse checks")
      ->group(stocs);
  cmd.add_option("--coarse-ratio", p.stocs.lcp.coarse_ratio,
                 "At the first coarse check, a hypothesis extrapolated below this share of the "
                 "score to beat is dropped")
      ->group(stocs);
  cmd.add_option("--instances", p.stocs.instances,
                 "Distinct poses per object (several instances of one object in a bin)")
      ->group(stocs);
  cmd.add_option("--instance-separation", p.stocs.instance_separation,
                 "Poses closer than this ADD-S, as a fraction of the diameter, are one instance")
      ->group(stocs);
  cmd.add_option("--icp", p.stocs.icp.enabled,
                 "Refine the best pose by point-to-plane ICP (true/false)")
      ->group(stocs);
  cmd.add_option("--icp-candidates", p.stocs.icp.candidates,
                 "Poses of this many best bases are refined; the best after refinement wins")
      ->group(stocs);
  cmd.add_option("--icp-iterations", p.stocs.icp.iterations, "ICP iterations")->group(stocs);
  cmd.add_option("--icp-screening", p.stocs.icp.screening_iterations,
                 "ICP steps every candidate takes before only the --icp-finalists best by "
                 "objective take the rest (0: every candidate takes every step)")
      ->group(stocs);
  cmd.add_option("--icp-finalists", p.stocs.icp.finalists,
                 "Candidates refined to the end after the screening steps")
      ->group(stocs);
  cmd.add_option("--icp-distance", p.stocs.icp.max_distance, "ICP correspondence radius, m")
      ->group(stocs);
  cmd.add_option("--free-space", p.stocs.free_space.enabled,
                 "Rank refined poses down by their surface in space the sensor sees through "
                 "(true/false)")
      ->group(stocs);
  cmd.add_option("--free-space-margin", p.stocs.free_space.margin,
                 "A model point in front of the measured surface by more than this is in free "
                 "space, m")
      ->group(stocs);
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
