#include "stocs/estimation/pose_proximity.h"

#include <algorithm>

namespace stocs {

PoseProximity::PoseProximity(const ObjectModel& model) {
  if (model.points.empty()) return;
  Eigen::Vector3f lo = model.points.front(), hi = lo;
  for (const Eigen::Vector3f& p : model.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  centre_ = (lo + hi) / 2;
  for (const Eigen::Vector3f& p : model.points) radius_ = std::max(radius_, (p - centre_).norm());
}

}  // namespace stocs
