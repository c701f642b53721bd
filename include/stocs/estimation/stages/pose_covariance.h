#pragma once
// The 6x6 covariance of a returned pose, from the point-to-plane normal equations at the final pose
// (the information matrix J^T W J of the refinement's rows) and the residual noise, regularised by
// a broad prior.
//
// Convention (geometry_msgs/PoseWithCovariance, REP 103): x, y, z of the pose's origin in metres,
// then rotation about the camera's x, y and z axes in radians (a small rotation applied on the
// left, R_true = exp(theta) R_estimate), all in the camera frame. The rows linearise about the
// posed model's centre; the covariance is moved to the pose's own origin (the model frame's, as
// BOP and TF report it), which couples translation with rotation when the origin lies off-centre.
//
// The correspondences of a dense sampling are not independent (neighbouring model samples share a
// segment voxel, its normal and its depth noise), and the residual does not show every error (a
// pose stopped a little short of the optimum, the model's sampling): the data's information is
// divided by kCorrelationFactor, calibrated on generated scenes (seeds 101-120) so that 90%
// ellipsoids hold about 90% of the true errors of correct poses (README, "Pose covariance").
//
// Directions the data does not constrain (rotation about a cylinder's axis, sliding along a flat
// face) have no information; the prior (the centre's position known to about the object's
// diameter, the rotation to about pi in each axis) keeps their variance that large instead of
// letting it be infinite, or falsely small by clipping. For an object with discrete symmetries the
// covariance is of the error to the nearest symmetric equivalent of the true pose: the data cannot
// tell the equivalents apart. A near symmetry (near_symmetries.h) is a second pose the data barely
// tells apart; the rotation about its axis and the position get variances that put the other pose
// at kNearSymmetrySigmas standard deviations.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

#include "stocs/estimation/stages/icp_refiner.h"
#include "stocs/model/near_symmetries.h"
#include "stocs/model/object_model.h"

namespace stocs {

using PoseCovariance = Eigen::Matrix<double, 6, 6>;

/// Inflation of the residual variance for correlated correspondences (see above): the 90%
/// ellipsoids of independent rows held 21% of the true errors.
constexpr double kCorrelationFactor = 10.0;
/// Lowest residual standard deviation believed, metres: below it the residual is sampling luck.
constexpr double kMinResidualStd = 0.0005;
/// A near symmetry's turn, in standard deviations of the rotation about its axis.
constexpr double kNearSymmetrySigmas = 2.0;

/// The covariance of the prior alone, at `pose` (translation std `diameter` at the model's centre
/// `centre`, camera frame, rotation std pi), in the convention above.
PoseCovariance priorCovariance(const Eigen::Isometry3f& pose, const Eigen::Vector3d& centre,
                               double diameter);

/// The covariance of `pose` from its normal equations (IcpRefiner::system at that pose), in the
/// convention above, widened about the model's near symmetries (model frame): the prior's where
/// the system has fewer than 7 rows or gives a non-finite result, so the covariance is always
/// finite, symmetric and positive definite.
PoseCovariance poseCovariance(const PointToPlaneSystem& system, const Eigen::Isometry3f& pose,
                              double diameter,
                              const std::vector<NearSymmetry>& near_symmetries = {});

/// The covariance of `pose` against the refiner's segment region `region` (one correspondence
/// pass, `near` as in IcpRefiner::refine), or the prior's without a refiner (ICP disabled).
PoseCovariance poseCovariance(const ObjectModel& model, const IcpRefiner* icp,
                              const Eigen::Isometry3f& pose, int region,
                              const LcpScorer* near = nullptr,
                              const std::vector<NearSymmetry>& near_symmetries = {});

}  // namespace stocs
