#include "stocs/model/near_symmetries.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "stocs/geometry/knn_index.h"

namespace stocs {
namespace {

constexpr float kExactShare = 0.2f;  // of the sampling radius: below, an exact symmetry
constexpr float kNearShare = 0.5f;   // of the sampling radius: below, a near symmetry
const float kNormalCos = std::cos(30.0f * static_cast<float>(M_PI) / 180.0f);

float meanDistance(const ObjectModel& model, const KnnIndex& index, const Eigen::Vector3f& centre,
                   const Eigen::Matrix3f& turn) {
  std::vector<size_t> nearest;
  std::vector<float> squared;
  double sum = 0;
  for (size_t i = 0; i < model.size(); ++i) {
    const Eigen::Vector3f p = centre + turn * (model.points[i] - centre);
    index.knn(p, 1, nearest, squared);
    if (nearest.empty()) continue;
    const size_t s = nearest[0];
    // On a surface facing the same way the in-plane offset is the sampling's, not the turn's.
    const bool along = (turn * model.normals[i]).dot(model.normals[s]) > kNormalCos;
    sum += along ? std::abs(model.normals[s].dot(p - model.points[s])) : std::sqrt(squared[0]);
  }
  return static_cast<float>(sum / static_cast<double>(model.size()));
}

}  // namespace

float turnedSurfaceDistance(const ObjectModel& model, const Eigen::Vector3f& axis, float angle) {
  if (model.size() == 0) return 0;
  const KnnIndex index(model.points);
  return meanDistance(model, index, sampleCentre(model),
                      Eigen::AngleAxisf(angle, axis.normalized()).toRotationMatrix());
}

std::vector<NearSymmetry> findNearSymmetries(const ObjectModel& model) {
  std::vector<NearSymmetry> out;
  if (model.size() < 4 || !(model.sampling_radius > 0)) return out;
  const Eigen::Vector3f centre = sampleCentre(model);
  Eigen::Matrix3f scatter = Eigen::Matrix3f::Zero();
  for (const Eigen::Vector3f& p : model.points) scatter += (p - centre) * (p - centre).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> principal(scatter);
  const KnnIndex index(model.points);
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3f axis = principal.eigenvectors().col(a).normalized();
    for (const int quarters : {1, 2}) {  // three quarters is the quarter turned back
      const float angle = static_cast<float>(M_PI / 2 * quarters);
      const float d =
          meanDistance(model, index, centre, Eigen::AngleAxisf(angle, axis).toRotationMatrix());
      if (d < kExactShare * model.sampling_radius || d >= kNearShare * model.sampling_radius)
        continue;
      out.push_back({axis, angle, d});
    }
  }
  return out;
}

}  // namespace stocs
