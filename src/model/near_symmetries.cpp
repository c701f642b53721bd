#include "stocs/model/near_symmetries.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "stocs/geometry/knn_index.h"

namespace stocs {
namespace {

constexpr float kExactShare = 0.2f;  // of the sampling radius: below, an exact symmetry
constexpr float kNearShare = 0.5f;   // of the sampling radius: below, a near symmetry
const float kNormalCos = std::cos(30.0f * static_cast<float>(M_PI) / 180.0f);

/// The turn by `angle` about `axis` (unit) through `centre`.
Eigen::Isometry3f turnAbout(const Eigen::Vector3f& centre, const Eigen::Vector3f& axis,
                            float angle) {
  Eigen::Isometry3f turn = Eigen::Isometry3f::Identity();
  turn.linear() = Eigen::AngleAxisf(angle, axis).toRotationMatrix();
  turn.translation() = centre - turn.linear() * centre;
  return turn;
}

float meanDistance(const ObjectModel& model, const KnnIndex& index,
                   const Eigen::Isometry3f& motion) {
  std::vector<size_t> nearest;
  std::vector<float> squared;
  double sum = 0;
  for (size_t i = 0; i < model.size(); ++i) {
    const Eigen::Vector3f p = motion * model.points[i];
    index.knn(p, 1, nearest, squared);
    if (nearest.empty()) continue;
    const size_t s = nearest[0];
    // On a surface facing the same way the in-plane offset is the sampling's, not the turn's.
    const bool along = (motion.linear() * model.normals[i]).dot(model.normals[s]) > kNormalCos;
    sum += along ? std::abs(model.normals[s].dot(p - model.points[s])) : std::sqrt(squared[0]);
  }
  return static_cast<float>(sum / static_cast<double>(model.size()));
}

Eigen::Matrix3f principalAxes(const ObjectModel& model, const Eigen::Vector3f& centre) {
  Eigen::Matrix3f scatter = Eigen::Matrix3f::Zero();
  for (const Eigen::Vector3f& p : model.points) scatter += (p - centre) * (p - centre).transpose();
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f>(scatter).eigenvectors();
}

constexpr size_t kAlignSamples = 500;  // a prefix of the random-order samples: unbiased
constexpr int kAlignSteps = 10;
constexpr float kAlternativeShare = 1.0f;  // of the sampling radius: below, an alternative
const float kDistinctAngle = 15.0f * static_cast<float>(M_PI) / 180.0f;

/// `motion` improved by point-to-point ICP of the first samples onto the model.
Eigen::Isometry3f alignOnto(const ObjectModel& model, const KnnIndex& index,
                            Eigen::Isometry3f motion) {
  const size_t n = std::min(kAlignSamples, model.size());
  Eigen::Matrix3Xd from(3, n), to(3, n);  // double: Eigen's float umeyama trips -Warray-bounds
  std::vector<size_t> nearest;
  std::vector<float> squared;
  for (int step = 0; step < kAlignSteps; ++step) {
    for (size_t i = 0; i < n; ++i) {
      const Eigen::Vector3f moved = motion * model.points[i];
      index.knn(moved, 1, nearest, squared);
      from.col(static_cast<Eigen::Index>(i)) = moved.cast<double>();
      to.col(static_cast<Eigen::Index>(i)) = model.points[nearest[0]].cast<double>();
    }
    const Eigen::Matrix4f step_fit = Eigen::umeyama(from, to, false).cast<float>();
    motion = Eigen::Isometry3f(step_fit) * motion;
  }
  return motion;
}

float rotationAngle(const Eigen::Matrix3f& r) {
  return Eigen::AngleAxisf(r).angle();
}

}  // namespace

namespace {

// Bounds the compositions (a lathe's turns and flips give 23; 47 leaves room for a shape more
// symmetric than the catalogue's).
constexpr size_t kMaxAlternatives = 47;

/// Adds `turn` to `out` when it fits (as it is, else aligned onto the model) and is distinct from
/// the identity and from every motion kept before.
void addIfAlternative(const ObjectModel& model, const KnnIndex& index,
                      const Eigen::Isometry3f& turn, std::vector<ShapeAlternative>& out) {
  const auto seen = [&](const Eigen::Isometry3f& motion) {
    return rotationAngle(motion.linear()) < kDistinctAngle ||  // identity, or pulled back to it
           std::any_of(out.begin(), out.end(), [&](const ShapeAlternative& s) {
             return rotationAngle(s.motion.linear().transpose() * motion.linear()) < kDistinctAngle;
           });
  };
  if (seen(turn)) return;
  // An exact turn stays as it is; one off the body's axis (a mug's) is aligned onto the model.
  Eigen::Isometry3f motion = turn;
  float shift = meanDistance(model, index, turn);
  if (shift >= kAlternativeShare * model.sampling_radius) {
    motion = alignOnto(model, index, turn);
    shift = meanDistance(model, index, motion);
  }
  if (shift >= kAlternativeShare * model.sampling_radius || seen(motion)) return;
  out.push_back(shapeAlternative(motion, shift));
}

}  // namespace

ShapeAlternative shapeAlternative(const Eigen::Isometry3f& motion, float shift) {
  const Eigen::AngleAxisf rotation(motion.linear());
  return {motion, rotation.axis(), rotation.angle(), shift};
}

std::vector<ShapeAlternative> findShapeAlternatives(const ObjectModel& model) {
  std::vector<ShapeAlternative> out;
  if (model.size() < 4 || !(model.sampling_radius > 0)) return out;
  const Eigen::Vector3f centre = sampleCentre(model);
  const Eigen::Matrix3f axes = principalAxes(model, centre);
  const KnnIndex index(model.points);
  for (int a = 0; a < 3; ++a) {
    // Half and quarter turns first: an exact one is kept as it is, before an aligned neighbour.
    for (const int step : {6, 3, 9, 1, 2, 4, 5, 7, 8, 10, 11}) {
      addIfAlternative(
          model, index,
          turnAbout(centre, axes.col(a).normalized(), static_cast<float>(M_PI / 6 * step)), out);
    }
  }
  // Compositions: a box's quarter turn about one axis after a half turn about another is a half
  // turn about a diagonal, which no principal axis gives.
  for (size_t i = 0; i < out.size() && out.size() < kMaxAlternatives; ++i) {
    for (size_t j = 0; j < out.size() && out.size() < kMaxAlternatives; ++j) {
      addIfAlternative(model, index, out[i].motion * out[j].motion, out);
    }
  }
  return out;
}

std::string ambiguityText(const std::vector<ShapeAlternative>& alternatives) {
  const float same_axis = std::cos(10.0f * static_cast<float>(M_PI) / 180.0f);
  std::vector<std::pair<Eigen::Vector3f, std::vector<int>>> axes;  // axis, angles in degrees
  for (const ShapeAlternative& a : alternatives) {
    const auto it = std::find_if(axes.begin(), axes.end(), [&](const auto& axis) {
      return std::abs(axis.first.dot(a.axis)) > same_axis;
    });
    // The same axis the other way round turns the other way.
    const float sign = it != axes.end() && it->first.dot(a.axis) < 0 ? -1.0f : 1.0f;
    const int degrees = static_cast<int>(std::lround(sign * a.angle * 180.0f / M_PI + 360)) % 360;
    if (it == axes.end()) {
      axes.push_back({a.axis, {degrees}});
    } else {
      it->second.push_back(degrees);
    }
  }
  std::string text = "fits as well turned by";
  for (size_t k = 0; k < axes.size(); ++k) {
    std::sort(axes[k].second.begin(), axes[k].second.end());
    const Eigen::Vector3f& v = axes[k].first;
    text += fmt::format("{} {} deg about model axis [{:.2f} {:.2f} {:.2f}]", k > 0 ? ";" : "",
                        fmt::join(axes[k].second, ", "), v.x(), v.y(), v.z());
  }
  return text;
}

float turnedSurfaceDistance(const ObjectModel& model, const Eigen::Vector3f& axis, float angle) {
  if (model.size() == 0) return 0;
  const KnnIndex index(model.points);
  return meanDistance(model, index, turnAbout(sampleCentre(model), axis.normalized(), angle));
}

std::vector<NearSymmetry> findNearSymmetries(const ObjectModel& model) {
  std::vector<NearSymmetry> out;
  if (model.size() < 4 || !(model.sampling_radius > 0)) return out;
  const Eigen::Vector3f centre = sampleCentre(model);
  const Eigen::Matrix3f axes = principalAxes(model, centre);
  const KnnIndex index(model.points);
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3f axis = axes.col(a).normalized();
    for (const int quarters : {1, 2}) {  // three quarters is the quarter turned back
      const float angle = static_cast<float>(M_PI / 2 * quarters);
      const float d = meanDistance(model, index, turnAbout(centre, axis, angle));
      if (d < kExactShare * model.sampling_radius || d >= kNearShare * model.sampling_radius)
        continue;
      out.push_back({axis, angle, d});
    }
  }
  return out;
}

}  // namespace stocs
