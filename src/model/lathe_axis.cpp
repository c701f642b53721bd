#include "stocs/model/lathe_axis.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace stocs {
namespace {

/// A lathe's step is below this angle; its double about the same axis within kSameStep.
const float kLatheStep = 45.0f * static_cast<float>(M_PI) / 180.0f;
const float kSameStep = 15.0f * static_cast<float>(M_PI) / 180.0f;
/// The share of the samples that the axis is fitted to: the rest, those its turn moves most along
/// their normals, are the parts that do not turn onto themselves (a mug's handle).
constexpr double kLatheBody = 0.75;
constexpr int kFitRounds = 4;

const ShapeAlternative* latheStep(const std::vector<ShapeAlternative>& alternatives) {
  for (const ShapeAlternative& a : alternatives) {
    if (a.angle >= kLatheStep) continue;
    const bool doubled =
        std::any_of(alternatives.begin(), alternatives.end(), [&](const ShapeAlternative& b) {
          return b.axis.dot(a.axis) > std::cos(kSameStep) &&
                 std::abs(b.angle - 2 * a.angle) < kSameStep;
        });
    if (doubled) return &a;
  }
  return nullptr;
}

/// Per sample, the derivative of its normal motion under a turn (w, v): w . (p x n) + v . n, with
/// p about `centre`.
std::vector<Eigen::Matrix<double, 6, 1>> motionRows(const ObjectModel& model,
                                                    const Eigen::Vector3d& centre) {
  std::vector<Eigen::Matrix<double, 6, 1>> rows(model.size());
  for (size_t i = 0; i < model.size(); ++i) {
    const Eigen::Vector3d p = model.points[i].cast<double>() - centre;
    const Eigen::Vector3d n = model.normals[i].cast<double>();
    rows[i] << p.cross(n), n;
  }
  return rows;
}

}  // namespace

Eigen::Isometry3f LatheAxis::turn(float angle) const {
  Eigen::Isometry3f motion = Eigen::Isometry3f::Identity();
  motion.linear() = Eigen::AngleAxisf(angle, axis).toRotationMatrix();
  motion.translation() = point - motion.linear() * point;
  return motion;
}

std::optional<LatheAxis> findLatheAxis(const ObjectModel& model,
                                       const std::vector<ShapeAlternative>& alternatives) {
  const ShapeAlternative* step = latheStep(alternatives);
  if (!step || model.size() == 0) return std::nullopt;
  const Eigen::Vector3d centre = sampleCentre(model).cast<double>();
  const std::vector<Eigen::Matrix<double, 6, 1>> rows = motionRows(model, centre);
  std::vector<double> moved(rows.size(), 0);  // per radian; all samples count in the first round
  Eigen::Vector3d w = Eigen::Vector3d::UnitZ(), v = Eigen::Vector3d::Zero();
  for (int round = 0; round < kFitRounds; ++round) {
    std::vector<double> sorted = moved;
    const auto body = sorted.begin() +
                      static_cast<std::ptrdiff_t>(kLatheBody * static_cast<double>(sorted.size()));
    std::nth_element(sorted.begin(), body, sorted.end());
    Eigen::Matrix<double, 6, 6> normal = Eigen::Matrix<double, 6, 6>::Zero();
    for (size_t i = 0; i < rows.size(); ++i) {
      if (round == 0 || moved[i] <= *body) normal += rows[i] * rows[i].transpose();
    }
    // The turn with the position following it as well as it can: the Schur complement.
    const Eigen::Matrix3d ww = normal.topLeftCorner<3, 3>(), wv = normal.topRightCorner<3, 3>();
    const Eigen::LDLT<Eigen::Matrix3d> slide(normal.bottomRightCorner<3, 3>());
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(ww -
                                                               wv * slide.solve(wv.transpose()));
    w = eigen.eigenvectors().col(0);
    v = -slide.solve(wv.transpose() * w);
    for (size_t i = 0; i < rows.size(); ++i) {
      moved[i] = std::abs(rows[i].head<3>().dot(w) + rows[i].tail<3>().dot(v));
    }
  }
  LatheAxis lathe;
  lathe.step = step->angle;
  lathe.shift = step->shift;
  const double off = static_cast<double>(model.sampling_radius) / lathe.step;
  lathe.handle =
      static_cast<float>(static_cast<double>(std::count_if(moved.begin(), moved.end(),
                                                           [&](double m) { return m > off; })) /
                         static_cast<double>(moved.size()));
  if (lathe.handle > 1 - kLatheBody) return std::nullopt;  // no body turns onto itself (a box)
  // Velocity w x (p - centre) + v; a slide along the axis leaves the line where it is.
  v -= v.dot(w) * w;
  lathe.point = (centre + w.cross(v)).cast<float>();
  lathe.axis = w.cast<float>();
  return lathe;
}

}  // namespace stocs
