#pragma once
// Symmetries of an object model, and the choice among the poses they make equivalent. StoCS returns
// any one of a symmetric object's equivalent poses; a consumer that follows the object over frames
// wants the same one every time, so the node publishes the equivalent nearest to the pose it
// published last for that object.

#include <Eigen/Geometry>
#include <map>
#include <vector>

namespace stocs_ros {

/// Rotation symmetry about an axis through a point, in the model frame (metres).
struct ContinuousSymmetry {
  Eigen::Vector3f axis = Eigen::Vector3f::UnitZ();  ///< unit
  Eigen::Vector3f offset = Eigen::Vector3f::Zero();
};

struct ObjectSymmetries {
  std::vector<Eigen::Isometry3f>
      discrete;  ///< model-frame transforms (metres), identity not listed
  std::vector<ContinuousSymmetry> continuous;

  bool empty() const { return discrete.empty() && continuous.empty(); }
};

/// Among pose * S for S in {identity, each discrete symmetry}, each followed by the best rotation
/// about every continuous axis in turn, the pose whose rotation is nearest to `reference`.
Eigen::Isometry3f nearestEquivalentPose(const Eigen::Isometry3f& pose,
                                        const Eigen::Isometry3f& reference,
                                        const ObjectSymmetries& symmetries);

/// Remembers the last published pose of each object and picks equivalents near it.
class SymmetricPoseTracker {
 public:
  /// The equivalent of `pose` nearest to the object's previous pose (the pose itself the first time
  /// or for an object without symmetries); it becomes the new previous pose.
  Eigen::Isometry3f track(size_t object, const Eigen::Isometry3f& pose,
                          const ObjectSymmetries& symmetries);

 private:
  std::map<size_t, Eigen::Isometry3f> previous_;
};

}  // namespace stocs_ros
