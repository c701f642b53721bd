#pragma once
// The symmetry group of an object as listed in BOP's models_info.json, as rigid transforms of the
// model frame (translations in mm) that leave the model's surface in place.

#include <vector>

#include "stocs/eval/pose_metrics.h"
#include "stocs/io/bop_dataset.h"

namespace stocs {

/// Identity, every discrete symmetry, and each continuous symmetry sampled in `continuous_steps`
/// rotations about its axis through its offset, composed with every discrete one as the BOP toolkit
/// does (continuous rotation applied after the discrete transform). With the default of 360 steps
/// the group is sampled every degree. Throws InputError when `continuous_steps` < 1 or an axis is
/// zero or not finite.
std::vector<RigidPose> symmetryTransformations(const BopObjectInfo& info,
                                               int continuous_steps = 360);

}  // namespace stocs
