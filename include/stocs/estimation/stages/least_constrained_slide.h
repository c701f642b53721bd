#pragma once
// Point-to-plane ICP barely feels a move along a direction the visible surface does not constrain
// (a box seen on its top and its long side slides along its length), so a refinement can stop
// millimetres off along it. The estimator's ranking (the objective times the share of the visible
// surface not in free space) does feel it: surface pushed past the object's measured end lies in
// front of what the sensor sees behind. This search moves the pose along its least constrained
// translation and keeps the best-ranked place; bestAlong searches a given direction.

#include <Eigen/Geometry>

#include "stocs/estimation/stages/free_space_check.h"
#include "stocs/estimation/stages/lcp_scorer.h"
#include "stocs/estimation/stages/pose_covariance.h"

namespace stocs {

/// Steps tried each way along the least constrained direction ...
constexpr int kSlideSteps = 4;
/// ... each this share of the model's diameter: up to 8% of it, within the 10% that makes a pose
/// right.
constexpr float kSlideStep = 0.02f;
/// A moved pose must rank higher than the pose by this factor: a refined pose stays where the
/// ranking barely differs.
constexpr float kSlideGain = 1.01f;
/// The search runs only where the covariance leaves the direction at least this many steps of
/// standard deviation: where the data fixes the pose better, a step would follow the ranking's
/// noise (a block seen on three faces moved 2.7 mm).
constexpr float kSlideLoose = 0.5f;

/// Of `pose` moved by k `step` for |k| <= `steps` (camera frame), the one ranked highest by
/// `scorer`'s objective on `region` times the share of the visible surface that `surface` does not
/// find in free space, where it ranks above `pose` itself by kSlideGain; else `pose`. A search of
/// the whole range, for poses compared with one another at their best places (a climb stops at the
/// ranking's first dip).
Eigen::Isometry3f bestAlong(const ObjectModel& model, const Eigen::Isometry3f& pose,
                            const Eigen::Vector3f& step, int steps, const LcpScorer& scorer,
                            const FreeSpaceCheck& surface, int region = -1);

/// `pose` moved along the translation `covariance` constrains least with the rotation held (the
/// weakest direction of its inverse's translational block, camera frame) in steps of kSlideStep
/// of the diameter, up to kSlideSteps, while each step ranks higher by `scorer`'s objective times
/// the share of the visible surface that `surface` does not find in free space (one way, then the
/// other if the first step did not); `pose` itself where neither first step does, or where that
/// direction's standard deviation is below kSlideLoose steps.
Eigen::Isometry3f slideAlongLeastConstrained(const ObjectModel& model,
                                             const Eigen::Isometry3f& pose,
                                             const PoseCovariance& covariance,
                                             const LcpScorer& scorer,
                                             const FreeSpaceCheck& surface);

}  // namespace stocs
