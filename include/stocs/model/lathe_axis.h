#pragma once
// A lathe's body (a mug's, a can's) turns onto itself by any angle about one axis line, so its
// shape alternatives come in steps about that axis, 30 degrees apart. Between the steps a handle
// straight behind the body stays hidden over a range of turns; judging the turns there needs the
// body's own axis: the steps' axes, aligned by ICP onto a model with a handle, lean towards it by
// up to 13 degrees, and turned about them the body moves off itself.

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "stocs/model/near_symmetries.h"
#include "stocs/model/object_model.h"

namespace stocs {

struct LatheAxis {
  Eigen::Vector3f point = Eigen::Vector3f::Zero();  ///< on the axis line, model frame
  Eigen::Vector3f axis = Eigen::Vector3f::UnitZ();  ///< unit
  float step = 0;   ///< radians: the smallest shape alternative's turn about the axis
  float shift = 0;  ///< metres: that alternative's ShapeAlternative::shift
  /// Share of the samples that a step moves by more than the sampling radius along their normals:
  /// the parts that do not turn onto themselves (the catalogue mug's handle about 5%, a can's 0).
  float handle = 0;

  /// The motion (model frame) turning by `angle` radians about the axis line.
  Eigen::Isometry3f turn(float angle) const;
};

/// The model's lathe axis, if `alternatives` (findShapeAlternatives) hold a lathe's step (a turn
/// below 45 degrees whose double about the same axis is there too) and at least three quarters of
/// the samples turn onto themselves by it (a box whose 30-degree turns pass the shape test is no
/// lathe). The axis is the motion (w, v) minimising sum (w . (p x n) + v . n)^2 over the samples,
/// |w| = 1, fitted again on the three quarters it moves least, four times. Deterministic.
std::optional<LatheAxis> findLatheAxis(const ObjectModel& model,
                                       const std::vector<ShapeAlternative>& alternatives);

}  // namespace stocs
