#include "stocs/eval/object_metrics.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include "stocs/eval/rt_error.h"
#include "stocs/eval/symmetries.h"
#include "stocs/geometry/mesh.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

std::vector<Eigen::Vector3f> nonEmpty(std::vector<Eigen::Vector3f> points) {
  if (points.empty()) throw InputError("object model without points");
  return points;
}

/// At most `count` of `points`, evenly spaced in their order (all of them when there are fewer).
std::vector<Eigen::Vector3f> evenlySpaced(const std::vector<Eigen::Vector3f>& points,
                                          size_t count) {
  if (points.size() <= count) return points;
  std::vector<Eigen::Vector3f> some;
  for (size_t k = 0; k < count; ++k) some.push_back(points[k * points.size() / count]);
  return some;
}

}  // namespace

TargetErrors::TargetErrors()
    : add_mm(std::numeric_limits<double>::infinity()),
      adds_mm(add_mm),
      mssd_mm(add_mm),
      rotation_deg(add_mm),
      translation_mm(add_mm) {}

double TargetErrors::mssdRecall() const {
  constexpr int kThresholds = 10;  // k / 20 of the diameter for k = 1..10: 0.05, 0.1, ..., 0.5
  int below = 0;
  for (int k = 1; k <= kThresholds; ++k) below += mssd_mm * 20 < k * diameter_mm;
  return static_cast<double>(below) / kThresholds;
}

ObjectMetrics::ObjectMetrics(std::vector<Eigen::Vector3f> points_mm, const BopObjectInfo& info)
    : adds_(nonEmpty(std::move(points_mm))),
      mssd_points_(evenlySpaced(adds_.points(), kMssdPoints)),
      symmetries_(symmetryTransformations(info)),
      diameter_mm_(info.diameter_mm > 0 ? info.diameter_mm : pointSetDiameter(adds_.points())),
      symmetric_(info.symmetric()) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3f& p : adds_.points()) sum += p.cast<double>();
  centroid_ = sum / adds_.points().size();
}

TargetErrors ObjectMetrics::evaluate(const RigidPose* estimate,
                                     const std::vector<RigidPose>& instances) const {
  if (instances.empty()) throw InputError("no ground-truth instance to compare with");
  TargetErrors e;
  e.diameter_mm = diameter_mm_;
  e.symmetric = symmetric_;
  if (!estimate) return e;
  if (!estimate->R.allFinite() || !estimate->t.allFinite()) {
    throw InputError("estimated pose has non-finite values");
  }
  // Nearest centres first, so that the first ADD-S is usually the smallest and the others stop
  // early (AddsMetric gives up once it is certain to exceed the best so far).
  const Eigen::Vector3d centre = estimate->R * centroid_ + estimate->t;
  std::vector<double> centre_distance;
  for (const RigidPose& g : instances)
    centre_distance.push_back((g.R * centroid_ + g.t - centre).norm());
  std::vector<int> order(instances.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return centre_distance[a] < centre_distance[b]; });
  for (int i : order) {
    const double adds = adds_.error(*estimate, instances[i], e.adds_mm);
    if (adds < e.adds_mm) {
      e.adds_mm = adds;
      e.instance = i;
    }
  }
  const RigidPose& truth = instances[e.instance];
  e.found = true;
  e.add_mm = addError(adds_.points(), *estimate, truth);
  e.mssd_mm = mssdError(mssd_points_, *estimate, truth, symmetries_);
  const RtError rt = rtError(*estimate, truth, symmetries_);
  e.rotation_deg = rt.rotation_deg;
  e.translation_mm = rt.translation_mm;
  return e;
}

}  // namespace stocs
