#pragma once
// What the two PCL 4PCS-family baselines (fpcs, kfpcs) share: the inputs, the parameters both take
// and the budget mapping (the table in four_pcs.cpp, with the documentation each value follows),
// and seeded, reproducible random draws.
//
// Bases are drawn on the target and congruent sets searched on the source, so the hard segment is
// the target and the model the source, as in StoCS (bases on the scene, congruent sets on the
// model); the final transformation maps the model into the camera frame.

// PCL's 4PCS seeds std::rand from the clock per OpenMP thread inside computeTransformation(), where
// no subclass can reach; built without OpenMP that code is single-threaded and Reseeded below makes
// it reproducible. The template is compiled here, so this file must never see -fopenmp.
#ifdef _OPENMP
#error "PCL's 4PCS is only reproducible without OpenMP; do not build src/methods with -fopenmp"
#endif

#include <pcl/point_types.h>
#include <pcl/registration/ia_fpcs.h>

#include <cstdlib>
#include <optional>

#include "baseline_method.h"

namespace stocs {

using FourPcs = pcl::registration::FPCSInitialAlignment<pcl::PointXYZ, pcl::PointXYZ>;

/// A PCL 4PCS aligner whose random draws follow `seed`. PCL's initCompute() seeds std::rand with
/// std::time (ia_fpcs.hpp), so every draw after it (base selection) is reseeded here. std::rand is
/// process-wide: runs are reproducible as long as nothing else draws from it at the same time.
template <class Aligner>
class Reseeded : public Aligner {
 public:
  explicit Reseeded(unsigned seed) : seed_(seed) {}

 protected:
  bool initCompute() override {
    const bool ok = Aligner::initCompute();
    std::srand(seed_);
    return ok;
  }

 private:
  unsigned seed_;
};

/// The seed given to Reseeded for a run seeded with `seed` (PipelineParams::stocs.seed).
unsigned fourPcsSeed(uint64_t seed);

/// Runs `aligner` on model samples drawn with the run's seed (the source) and the hard segment (the
/// target) with the shared settings (four_pcs.cpp).
/// Returns the final transformation with score = 1 - PCL's fitness score, or nothing when PCL
/// found no candidate.
std::optional<BaselineHypothesis> alignFourPcs(FourPcs& aligner, const SoftSegment& segment,
                                               const ObjectInput& input);

}  // namespace stocs
