#pragma once
// A pose's covariance as published: checked (never a NaN or a covariance that is not positive
// definite on the wire: those fall back to the prior of stocs/estimation/stages/pose_covariance.h),
// and shown in rviz as the ellipsoid holding the object's origin with 90% probability.

#include <std_msgs/ColorRGBA.h>
#include <visualization_msgs/Marker.h>
#include <Eigen/Geometry>
#include <boost/array.hpp>

#include "stocs/estimation/stages/pose_covariance.h"
#include "stocs/model/object_model.h"

namespace stocs_ros {

/// `covariance` when it is finite and positive definite, else the prior's at `pose` for `model`.
stocs::PoseCovariance publishableCovariance(const stocs::PoseCovariance& covariance,
                                            const Eigen::Isometry3f& pose,
                                            const stocs::ObjectModel& model);

/// Row-major, as geometry_msgs/PoseWithCovariance::covariance.
boost::array<double, 36> covarianceMsg(const stocs::PoseCovariance& covariance);

/// A SPHERE at the pose's origin, its axes the eigenvectors of the position covariance (the
/// top-left 3x3 block) and its diameters those of the 90% ellipsoid (2 sqrt(chi2_3(0.9) lambda)),
/// in `colour` made translucent; a diameter below `minimum_diameter` is drawn at that size (so
/// that it shows around the object). Namespace, id and header are the caller's. Expects a
/// publishable covariance.
visualization_msgs::Marker uncertaintyMarker(const Eigen::Isometry3f& pose,
                                             const stocs::PoseCovariance& covariance,
                                             std_msgs::ColorRGBA colour,
                                             double minimum_diameter = 0);

}  // namespace stocs_ros
