#include "stocs/estimation/stages/icp_refiner.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "stocs/util/error.h"

namespace stocs {
namespace {

// Steps below these end the iterations (radians; metres: 0.05 mm).
constexpr double kConvergedRotation = 1e-4;
constexpr double kConvergedTranslation = 5e-5;
// Largest difference of pose matrix entries taken as a return to an earlier pose.
constexpr float kCycleTolerance = 1e-6f;

}  // namespace

const ParamSet<IcpParams>& IcpParams::schema() {
  static const ParamSet<IcpParams> schema =
      ParamSet<IcpParams>()
          .add(&IcpParams::enabled, "enabled", "refine the best hypotheses by point-to-plane ICP")
          .flag("--icp")
          .add(&IcpParams::iterations, "iterations", "", ParamRange::closed(0, 1000),
               "ICP steps at most")
          .flag("--icp-iterations")
          .add(&IcpParams::max_distance, "max_distance", "m", ParamRange::aboveUpTo(0, 0.2),
               "correspondence radius")
          .flag("--icp-distance")
          .add(&IcpParams::normal_angle_deg, "normal_angle_deg", "deg",
               ParamRange::aboveUpTo(0, 180), "correspondences need normals within this angle")
          .add(&IcpParams::candidates, "candidates", "", ParamRange::closed(1, 1000),
               "poses of this many best bases are refined; the best refined one wins")
          .flag("--icp-candidates")
          .add(
              &IcpParams::screening_iterations, "screening_iterations", "",
              ParamRange::closed(0, 1000),
              "every candidate takes these steps first, only the finalists the rest; 0: every step")
          .flag("--icp-screening")
          .add(&IcpParams::finalists, "finalists", "", ParamRange::closed(1, 1000),
               "candidates refined to the end after the screening steps")
          .flag("--icp-finalists");
  return schema;
}

void IcpParams::validate() const {
  schema().validate(*this);
}

IcpRefiner::IcpRefiner(const SoftSegment& segment, const IcpParams& params)
    : segment_(segment),
      params_((params.validate(), params)),
      grids_(segment.points, segment.region, params.max_distance),
      cos_normal_(std::cos(params.normal_angle_deg * static_cast<float>(M_PI) / 180.0f)) {}

Eigen::Isometry3f refinePointToPlane(const ObjectModel& model, const SoftSegment& segment,
                                     const Eigen::Isometry3f& pose, int region,
                                     const IcpParams& params) {
  return IcpRefiner(segment, params).refine(model, pose, region);
}

Eigen::Isometry3f IcpRefiner::refine(const ObjectModel& model, const Eigen::Isometry3f& pose,
                                     int region, const LcpScorer* near) const {
  IcpRun run(pose);
  iterate(model, run, params_.iterations, region, near);
  return run.pose;
}

PointToPlaneSystem IcpRefiner::system(const ObjectModel& model, const Eigen::Isometry3f& pose,
                                      int region, const LcpScorer* near) const {
  const SoftSegment& segment = segment_;
  if (near && (&near->segment() != &segment || near->params().distance > params_.max_distance)) {
    near = nullptr;
  }
  // Most correspondences of a pose close to its optimum lie within delta_s: those take the short
  // lists of the scorer's grid, and only the others the long lists of the correspondence radius.
  const NeighbourhoodGrid& grid = grids_.of(region);
  auto closest = [&](const Eigen::Vector3f& p) {
    const int s = near ? near->closest(p, region) : -1;
    return s >= 0 ? s : grid.closest(p);
  };
  // Linearised point-to-plane step: residual n.(p - s) with p moved by a small rotation w about
  // the model's centre c and a translation v has Jacobian [(p - c) x n, n]. About the camera
  // origin instead, a metre away, a rotation of w radians misplaces the model by |w|^2 / 2 metres
  // beyond the linear model (5 mm at 0.1 rad), and the iterations wander instead of converging.
  PointToPlaneSystem sys;
  sys.centre = (pose * sampleCentre(model)).cast<double>();
  const Eigen::Vector3d& c = sys.centre;
  for (size_t i = 0; i < model.size(); ++i) {
    const Eigen::Vector3f p = pose * model.points[i];
    const Eigen::Vector3f n = pose.linear() * model.normals[i];
    if (n.dot(p) >= 0) continue;  // faces away from the camera: cannot be observed
    const int s = closest(p);
    if (s < 0 || n.dot(segment.normals[s]) < cos_normal_) continue;
    const Eigen::Vector3d ns = segment.normals[s].cast<double>();
    const Eigen::Vector3d pd = p.cast<double>();
    Eigen::Matrix<double, 6, 1> j;
    j << (pd - c).cross(ns), ns;
    const double w = segment.confidence[s];
    const double r = ns.dot(pd - segment.points[s].cast<double>());
    sys.jtj += w * j * j.transpose();
    sys.jtr += w * j * r;
    sys.weighted_squares += w * r * r;
    ++sys.used;
  }
  return sys;
}

void IcpRefiner::iterate(const ObjectModel& model, IcpRun& run, int until, int region,
                         const LcpScorer* near) const {
  Eigen::Isometry3f& current = run.pose;
  for (until = std::min(until, params_.iterations); !run.finished && run.iterations < until;
       ++run.iterations) {
    const PointToPlaneSystem sys = system(model, current, region, near);
    const Eigen::Vector3d& c = sys.centre;
    if (sys.used < 6) {
      run.finished = true;
      break;
    }
    const Eigen::Matrix<double, 6, 1> x = sys.jtj.ldlt().solve(-sys.jtr);
    if (!x.allFinite()) {
      run.finished = true;
      break;
    }
    const Eigen::Vector3d w = x.head<3>();
    Eigen::Isometry3f step = Eigen::Isometry3f::Identity();
    if (w.norm() > 0)
      step.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix().cast<float>();
    step.translation() = (c + x.tail<3>()).cast<float>() - step.linear() * c.cast<float>();
    const Eigen::Isometry3f next = step * current;
    // Converged: the step moves the model by well under the sensor's resolution. Or cycling: the
    // correspondences flip between two sets and the step returns to the pose of two steps back.
    const bool cycling =
        run.iterations >= 1 &&
        (next.matrix() - run.before_last.matrix()).cwiseAbs().maxCoeff() < kCycleTolerance;
    run.before_last = current;
    current = next;
    run.finished =
        (w.norm() < kConvergedRotation && x.tail<3>().norm() < kConvergedTranslation) || cycling;
  }
}

}  // namespace stocs
