#pragma once
// An object's declared symmetries (the node's `symmetries`, or BOP's models_info.json): the poses
// they relate are one pose to any user of the object. StoCS returns any one of them; every output
// gives the same one: the equivalent nearest a track's previous pose, else a canonical one.

#include <Eigen/Geometry>
#include <vector>

namespace stocs {

/// Rotation symmetry about an axis through a point, in the model frame (metres).
struct SymmetryAxis {
  Eigen::Vector3f axis = Eigen::Vector3f::UnitZ();  ///< unit
  Eigen::Vector3f offset = Eigen::Vector3f::Zero();
};

struct ObjectSymmetries {
  std::vector<Eigen::Isometry3f>
      discrete;  ///< model-frame transforms (metres), identity not listed
  std::vector<SymmetryAxis> continuous;

  bool empty() const { return discrete.empty() && continuous.empty(); }
};

/// Among pose * S for S in {identity, each discrete symmetry}, each followed by the best rotation
/// about every continuous axis in turn, the pose whose rotation is nearest to `reference`'s.
Eigen::Isometry3f nearestEquivalentPose(const Eigen::Isometry3f& pose,
                                        const Eigen::Isometry3f& reference,
                                        const ObjectSymmetries& symmetries);

/// The equivalent whose rotation is nearest the camera's axes (nearestEquivalentPose to the
/// identity): the same choice in every frame for an object that stays put.
Eigen::Isometry3f canonicalPose(const Eigen::Isometry3f& pose, const ObjectSymmetries& symmetries);

/// Whether `motion` (model frame) is one of the symmetries: a pose moved by it is an equivalent
/// within `angle` radians and `distance` metres at the model point `centre`.
bool isSymmetry(const Eigen::Isometry3f& motion, const ObjectSymmetries& symmetries,
                const Eigen::Vector3f& centre, float angle, float distance);

}  // namespace stocs
