#include "alternative_choice.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>

#include "stocs/estimation/pose_proximity.h"
#include "stocs/estimation/stages/colour_agreement.h"
#include "stocs/estimation/stages/least_constrained_slide.h"
#include "stocs/estimation/stages/pose_covariance.h"
#include "stocs/geometry/knn_index.h"
#include "stocs/segmentation/support_plane.h"

namespace stocs {
namespace {

/// A shape alternative this close in rotation to a declared symmetry is that symmetry.
const float kSymmetryAngle = 5.0f * static_cast<float>(M_PI) / 180.0f;
/// Two refined candidates closer in rotation are one pose.
const float kDistinctAngle = 15.0f * static_cast<float>(M_PI) / 180.0f;

/// A candidate pose of one instance, refined and judged.
struct Candidate {
  explicit Candidate(const Eigen::Isometry3f& at, float from_shift = 0)
      : pose(at), refined(at), shift(from_shift) {}

  Eigen::Isometry3f pose;     ///< where it is judged: `refined`, or slid from it (slideNearBest)
  Eigen::Isometry3f refined;  ///< where ICP left it: the pose published
  std::optional<IcpRun> run;  ///< its refinement, once begun
  float shift = 0;            ///< of the shape alternative it came from (0: the instance itself)
  LcpDetail lcp;
  float free = 0;         ///< share of the visible surface in free space
  float unexplained = 0;  ///< share of the segment (by network probability) far from the surface
  /// Where the measured surface confirms its visible surface: one pixel per cell (onePerCell).
  std::vector<int> confirmed;
  float left_out = 0;  ///< the confirmed surface it leaves out, as a share of its own (leftOut)
  ColourAgreement colour;
  /// The share of its samples facing the camera that the segment matches: the objective without
  /// the model's sampling density, for a point model (ObjectModel::even_sampling); NaN for a mesh.
  float matched_share = std::numeric_limits<float>::quiet_NaN();
  /// Signed distance of its lowest point from the plane under the object (NaN: no plane) ...
  float height = std::numeric_limits<float>::quiet_NaN();
  /// ... and the share of its surface samples that lie on the plane (within kSupportNoise).
  float footing = 0;
  float unsupported =
      0;  ///< 0 to 1: how far it floats over or sinks into the plane (markUnsupported)
  float judgement = 0;  ///< higher is better
};

/// Shape alternatives fit the segment's shape alike by construction, so their objectives differ by
/// ICP's noise, which would drown the colour's evidence: the fit only rules out an alternative
/// that fits clearly worse than the instance (below this share of its objective and of its
/// ranking).
constexpr float kFitFloor = 0.9f;

/// The estimator's ranking of a pose (StocsEstimator::search): its objective times the share of its
/// visible surface not in free space; here also times 1 - how far it is from resting (unsupported).
float ranking(const Candidate& c) {
  return c.lcp.score * (1 - c.free) * (1 - c.unsupported);
}

/// Within the floor by ranking: a turn that explains a little less of the segment but puts no
/// handle over the table the camera sees fits as the estimator ranks poses. Or by objective alone:
/// a screened alternative's free share is that of a pose ICP has not settled yet (a flipped box
/// still off its face). Or, for a point model, as the data see it: it leaves no more of the segment
/// unexplained and the segment matches as large a share of its visible samples (a turn showing a
/// face the scan sampled sparsely; a mesh's samples are even, and fewer of them mean less surface).
bool fits(const Candidate& c, const Candidate& instance) {
  return c.lcp.score >= kFitFloor * instance.lcp.score ||
         ranking(c) >= kFitFloor * ranking(instance) ||
         (c.unexplained <= instance.unexplained + kAlternativeTie &&
          c.matched_share >= kFitFloor * instance.matched_share);
}

/// Measured surface that some candidate's visible surface meets (CandidateMeasure).
struct ConfirmedSurface {
  std::vector<Eigen::Vector3f> points;  ///< one per cell of an even subsample, camera frame
  size_t cells = 0;                     ///< that `points` stand for
};

/// Confirmed surface is counted in square cells of this many pixels a side: candidates turned
/// alike sample one surface at different pixels, and the cells count it once.
constexpr int kCellPixels = 4;

constexpr size_t kExplainedPoints = 300;  // segment or surface points checked, an even subsample

/// A candidate is placed along a lathe's axis at the best of the places within this many steps
/// either way ...
constexpr int kPlacementSteps = 5;
/// ... of this share of the diameter (up to 5% of it: the few millimetres ICP leaves a turn off).
constexpr float kPlacementStep = 0.01f;
/// A lathe is slid along its axis only where the axis lies at least this far (a sine: 30 degrees)
/// out of the normal of the plane under it.
constexpr float kSlideAlongPlane = 0.5f;

/// The plane under an object is fitted to about this many measured points around it ...
constexpr size_t kSupportPoints = 2000;
/// ... those within this distance of it lie on it (metres: a depth sensor's noise at a metre) ...
constexpr float kSupportTolerance = 0.004f;
/// ... and it is a support where at least this share of them do (a table seen beside the object).
constexpr float kSupportShare = 0.25f;
/// A candidate rests on the plane where its lowest point lies within this of it (metres: the
/// objective's delta_s) with at least kFooting of its surface samples on it: a face, not the edge
/// of a tilted turn under an object held over the table ...
constexpr float kResting = 0.005f;
constexpr float kFooting = 0.03f;
/// ... and a candidate whose lowest point lies farther from the plane than a resting one's by more
/// than this (metres: depth noise on a refined pose) floats over it or sinks into it.
constexpr float kSupportNoise = 0.002f;

/// What the data says of a candidate pose: the segment's shape under it (objective), the measured
/// surface (free space), the segment points it leaves unexplained (a handle seen where the pose
/// has none), and the measured surface that another candidate's surface meets but its own does
/// not (a handle seen outside the segment, where a candidate turned the right way puts its own).
class CandidateMeasure {
 public:
  CandidateMeasure(const SoftSegment& segment, const RefinementContext& context,
                   const FrameEvidence& evidence)
      : segment_(segment),
        context_(context),
        evidence_(evidence),
        model_index_(context.model.points),
        reach_(context.model.sampling_radius + context.scorer.params().distance) {
    const size_t stride = std::max<size_t>(1, segment.size() / kExplainedPoints);
    for (size_t i = 0; i < segment.size(); i += stride) checked_.push_back(i);
  }

  /// Measures `c` on the segment's `region` (-1: all of it), over the plane under the object
  /// (supportUnder; null: none).
  void operator()(Candidate& c, int region, const Plane* support) const {
    c.lcp = context_.scorer.detail(context_.model, c.pose, region);
    if (!context_.model.even_sampling && c.lcp.facing > 0) {
      c.matched_share = static_cast<float>(c.lcp.matched) / static_cast<float>(c.lcp.facing);
    }
    c.unexplained = unexplained(c.pose, region);
    if (evidence_.surface) {
      compareSurface(c);
      c.colour = colourAgreement(context_.model, c.pose, *evidence_.surface, evidence_.colour);
    }
    if (support) std::tie(c.height, c.footing) = onPlane(*support, c.pose);
  }

  /// `c` moved along `axis` (model frame), within the plane under it where there is one (a can
  /// standing on its end keeps its height), to the place within kPlacementSteps of kPlacementStep
  /// of the diameter where the estimator's ranking is highest (bestAlong), and measured again there
  /// if it moved. Whether it moved.
  bool slide(Candidate& c, const Eigen::Vector3f& axis, int region, const Plane* support) const {
    if (!evidence_.surface) return false;
    Eigen::Vector3f direction = c.pose.linear() * axis;
    if (support) direction -= direction.dot(support->normal) * support->normal;
    if (direction.norm() < kSlideAlongPlane) return false;
    const Eigen::Vector3f step =
        direction.normalized() * (kPlacementStep * context_.model.diameter);
    const Eigen::Isometry3f moved = bestAlong(context_.model, c.pose, step, kPlacementSteps,
                                              context_.scorer, *evidence_.surface, region);
    if (moved.translation() == c.pose.translation()) return false;
    c.pose = moved;
    (*this)(c, region, support);
    return true;
  }

  /// The plane the object at `pose` rests on, if any: fitted to the measured surface around it
  /// (within its diameter of its centre's pixel, its own surface at `pose` left out), and under it
  /// (its centre on the camera's side).
  std::optional<Plane> supportUnder(const Eigen::Isometry3f& pose) const {
    if (!evidence_.surface) return std::nullopt;
    const OrganizedCloud& cloud = evidence_.surface->cloud();
    const CameraIntrinsics& camera = evidence_.surface->camera();
    const Eigen::Vector3f centre = pose * sampleCentre(context_.model);
    if (!(centre.z() > 0)) return std::nullopt;
    const Eigen::Vector2f at = camera.project(centre);
    const float reach_px = static_cast<float>(camera.fx) * context_.model.diameter / centre.z();
    const int u0 = std::max(0, static_cast<int>(at.x() - reach_px));
    const int v0 = std::max(0, static_cast<int>(at.y() - reach_px));
    const int u1 = std::min(cloud.width - 1, static_cast<int>(at.x() + reach_px));
    const int v1 = std::min(cloud.height - 1, static_cast<int>(at.y() + reach_px));
    if (u1 < u0 || v1 < v0) return std::nullopt;
    const double area = static_cast<double>(u1 - u0 + 1) * (v1 - v0 + 1);
    const int stride = std::max(1, static_cast<int>(std::sqrt(area / kSupportPoints)));
    const Eigen::Isometry3f to_model = pose.inverse();
    std::vector<Eigen::Vector3f> around;
    for (int v = v0; v <= v1; v += stride) {
      for (int u = u0; u <= u1; u += stride) {
        const int index = v * cloud.width + u;
        if (cloud.isValid(index) && !nearModel(to_model * cloud.points[index])) {
          around.push_back(cloud.points[index]);
        }
      }
    }
    const auto min_inliers = static_cast<size_t>(kSupportShare * static_cast<float>(around.size()));
    std::optional<Plane> plane = dominantPlane(around, kSupportTolerance, min_inliers);
    if (plane && !(plane->distance(centre) > 0)) plane.reset();
    return plane;
  }

  /// The measured surface in the cells where the surface of a candidate that fits (kFitFloor) is
  /// confirmed.
  ConfirmedSurface confirmedSurface(const std::vector<Candidate>& candidates) const {
    if (!evidence_.surface) return {};
    std::vector<int> pixels;
    for (const Candidate& c : candidates) {
      if (fits(c, candidates.front())) {
        pixels.insert(pixels.end(), c.confirmed.begin(), c.confirmed.end());
      }
    }
    pixels = onePerCell(std::move(pixels));
    ConfirmedSurface out;
    out.cells = pixels.size();
    const size_t stride = std::max<size_t>(1, pixels.size() / kExplainedPoints);
    for (size_t k = 0; k < pixels.size(); k += stride) {
      out.points.push_back(evidence_.surface->cloud().points[static_cast<size_t>(pixels[k])]);
    }
    return out;
  }

  /// The cells of `surface` farther than the LCP distance from `c`'s model surface, as a share of
  /// the cells where `c`'s own surface is confirmed (at most 1): a turn that hides the handle the
  /// sensor sees, which another turn's confirmed surface holds. Shares below kAlternativeTie are
  /// the noise of the candidates' outlines and count 0.
  float leftOut(const Candidate& c, const ConfirmedSurface& surface) const {
    if (surface.points.empty()) return 0;
    size_t far = 0;
    const Eigen::Isometry3f to_model = c.pose.inverse();
    for (const Eigen::Vector3f& p : surface.points) far += !nearModel(to_model * p);
    const double left_out = static_cast<double>(far) / static_cast<double>(surface.points.size()) *
                            static_cast<double>(surface.cells);
    const double share =
        std::min(1.0, left_out / static_cast<double>(std::max<size_t>(1, c.confirmed.size())));
    return share < kAlternativeTie ? 0.0f : static_cast<float>(share);
  }

 private:
  /// `c`'s visible surface against the measured one: its share in free space and its confirmed
  /// cells.
  void compareSurface(Candidate& c) const {
    const int width = evidence_.surface->cloud().width;
    const ObjectModel& model = context_.model;
    int seen = 0, free = 0;
    std::vector<int> confirmed;
    evidence_.surface->visit(model, c.pose, [&](size_t, int u, int v, SampleView view) {
      ++seen;
      free += view == SampleView::kFree;
      if (view == SampleView::kConfirmed) confirmed.push_back(v * width + u);
    });
    c.free = seen == 0 ? 0.0f : static_cast<float>(free) / static_cast<float>(seen);
    c.confirmed = onePerCell(std::move(confirmed));
  }

  /// `pixels` (indices into the cloud) with one pixel kept per cell, in the cells' order.
  std::vector<int> onePerCell(std::vector<int> pixels) const {
    const int width = evidence_.surface->cloud().width;
    const auto cell = [&](int pixel) {
      return (pixel / width / kCellPixels) * (width / kCellPixels + 1) +
             pixel % width / kCellPixels;
    };
    std::sort(pixels.begin(), pixels.end(), [&](int a, int b) {
      return std::make_pair(cell(a), a) < std::make_pair(cell(b), b);
    });
    pixels.erase(
        std::unique(pixels.begin(), pixels.end(), [&](int a, int b) { return cell(a) == cell(b); }),
        pixels.end());
    return pixels;
  }

  /// The model at `pose` against `plane`: its lowest sample's signed distance, and the share of
  /// its samples within kSupportNoise of it.
  std::pair<float, float> onPlane(const Plane& plane, const Eigen::Isometry3f& pose) const {
    float lowest = std::numeric_limits<float>::infinity();
    size_t on = 0;
    for (const Eigen::Vector3f& p : context_.model.points) {
      const float height = plane.distance(pose * p);
      lowest = std::min(lowest, height);
      on += std::abs(height) <= kSupportNoise;
    }
    const size_t samples = std::max<size_t>(1, context_.model.points.size());
    return {lowest, static_cast<float>(on) / static_cast<float>(samples)};
  }

  bool nearModel(const Eigen::Vector3f& in_model) const {
    return model_index_.nearestDistanceSq(in_model) <= reach_ * reach_;
  }

  float unexplained(const Eigen::Isometry3f& pose, int region) const {
    const Eigen::Isometry3f to_model = pose.inverse();
    double far = 0, all = 0;
    for (const size_t i : checked_) {
      if (region >= 0 && !segment_.region.empty() && segment_.region[i] != region) continue;
      const float weight = segment_.confidence[i];
      all += weight;
      if (!nearModel(to_model * segment_.points[i])) far += weight;
    }
    return all > 0 ? static_cast<float>(far / all) : 0;
  }

  const SoftSegment& segment_;
  const RefinementContext& context_;
  const FrameEvidence& evidence_;
  const KnnIndex model_index_;
  const float reach_;
  std::vector<size_t> checked_;
};

/// The alternatives of `model` that are distinct poses: not a declared symmetry (the same pose),
/// nor one kept before followed by a declared symmetry (the same pose as that one).
std::vector<const ShapeAlternative*> distinctAlternatives(const PreparedModel& model) {
  std::vector<const ShapeAlternative*> out;
  const Eigen::Vector3f centre = sampleCentre(model.model);
  const float distance = model.model.sampling_radius;
  for (const ShapeAlternative& a : model.shape_alternatives) {
    if (isSymmetry(a.motion, model.symmetries, centre, kSymmetryAngle, distance)) continue;
    const bool kept = std::any_of(out.begin(), out.end(), [&](const ShapeAlternative* k) {
      return isSymmetry(k->motion.inverse() * a.motion, model.symmetries, centre, kDistinctAngle,
                        distance);
    });
    if (!kept) out.push_back(&a);
  }
  return out;
}

/// Screening steps after which an alternative that ICP has brought onto a candidate before it (the
/// instance, or an alternative from another turn) is dropped: it would follow that one's steps.
constexpr int kFirstLook = 3;

/// `candidates` less those that lie within the sampling radius (no model point farther) of one
/// before them: a box's turns by a third or a quarter mostly slide back onto the instance or its
/// half turns.
void dropRepeats(std::vector<Candidate>& candidates, const PoseProximity& proximity,
                 float distance) {
  std::vector<Candidate> kept;
  kept.reserve(candidates.size());
  for (Candidate& c : candidates) {
    const bool repeat = std::any_of(kept.begin(), kept.end(), [&](const Candidate& k) {
      return proximity.within(k.pose, c.pose, distance);
    });
    if (!repeat) kept.push_back(std::move(c));
  }
  candidates = std::move(kept);
}

/// `c` refined by ICP on to `steps` steps in all; adds the steps taken to `taken`.
void refine(Candidate& c, int region, int steps, const RefinementContext& context, long& taken) {
  if (!context.icp) return;
  if (!c.run) c.run.emplace(c.pose);
  const int before = c.run->iterations;
  context.icp->iterate(context.model, *c.run, steps, region, &context.scorer);
  taken += c.run->iterations - before;
  c.pose = c.refined = c.run->pose;
}

/// Sets each candidate's `unsupported`, 0 to 1: how much farther its lowest point lies from the
/// plane under the object than the nearest resting candidate's (kResting, kFooting), from
/// kSupportNoise (0) to twice it (1); all 0 where none rests on a plane (an object held or on
/// another, or no plane found).
void markUnsupported(std::vector<Candidate>& candidates) {
  float nearest = std::numeric_limits<float>::infinity();
  for (const Candidate& c : candidates) {
    if (std::isfinite(c.height) && c.footing >= kFooting) {
      nearest = std::min(nearest, std::abs(c.height));
    }
  }
  for (Candidate& c : candidates) c.unsupported = 0;
  if (!(nearest <= kResting)) return;
  for (Candidate& c : candidates) {
    const float excess = std::abs(c.height) - nearest - kSupportNoise;
    if (excess > 0) c.unsupported = std::min(1.0f, excess / kSupportNoise);
  }
}

/// The candidates' judgements (the instance first): less the shares in free space, of the segment
/// left unexplained and of the confirmed surface left out, and how far it is from resting on the
/// plane under the object where another rests on it (unsupported), plus the colour agreement where
/// every candidate has colour evidence; where only some have (a model coloured from frames that
/// saw one side), how much better than chance their colours agree (colourEvidence), 0 for the
/// others. -1 for an alternative below kFitFloor.
void judge(std::vector<Candidate>& candidates) {
  const bool coloured = std::all_of(candidates.begin(), candidates.end(),
                                    [](const Candidate& c) { return c.colour.evidence; });
  for (Candidate& c : candidates) {
    const float colour = coloured ? c.colour.agreement : colourEvidence(c.colour);
    c.judgement = (fits(c, candidates.front()) ? 0.0f : -1.0f) - c.free - c.unexplained -
                  c.left_out - c.unsupported + colour;
  }
}

/// The motion (model frame) from `from` to `to`, as a shape alternative.
ShapeAlternative motionBetween(const Eigen::Isometry3f& from, const Candidate& to) {
  return shapeAlternative(from.inverse() * to.pose, to.shift);
}

/// Index of the candidate to keep: 0, the instance itself, unless an alternative is judged better
/// by at least kAlternativeTie (switching needs evidence; in a tie StoCS's own ranking stands).
size_t chosen(const std::vector<Candidate>& candidates) {
  const auto best = std::max_element(
      candidates.begin(), candidates.end(),
      [](const Candidate& a, const Candidate& b) { return a.judgement < b.judgement; });
  return best->judgement - candidates.front().judgement >= kAlternativeTie
             ? static_cast<size_t>(best - candidates.begin())
             : 0;
}

/// A candidate's judgement less its support: what the data say of it, without the prior that
/// objects rest (an object held just over the table fits as well as a turn that would rest).
float withoutSupport(const Candidate& c) {
  return c.judgement + c.unsupported;
}

/// Adds `a` to `out` unless it is no turn, a declared symmetry or one listed before.
void addNamed(const ShapeAlternative& a, const PreparedModel& model,
              std::vector<ShapeAlternative>& out) {
  if (a.angle < kDistinctAngle) return;  // the same pose
  // The samples' centre (a pass over them) only where symmetries are declared.
  if (!model.symmetries.empty() && isSymmetry(a.motion, model.symmetries, sampleCentre(model.model),
                                              kDistinctAngle, model.model.sampling_radius)) {
    return;
  }
  const bool listed = std::any_of(out.begin(), out.end(), [&](const ShapeAlternative& o) {
    return Eigen::AngleAxisf(o.motion.linear().transpose() * a.motion.linear()).angle() <
           kDistinctAngle;
  });
  if (!listed) out.push_back(a);
}

/// Adds to `out` the candidates that fit as well as `best` (without the support: a track keeps the
/// turn it follows among them; judged `reference` where that is lower), as motions from it: each a
/// pose of its own (not `best` again after refinement, not a declared symmetry of it, not one
/// listed before).
void addEquallyFitting(const std::vector<Candidate>& candidates, const Candidate& best,
                       const PreparedModel& model, std::vector<ShapeAlternative>& out,
                       float reference = std::numeric_limits<float>::infinity()) {
  const float judged = std::min(withoutSupport(best), reference);
  for (const Candidate& c : candidates) {
    if (judged - withoutSupport(c) < kAlternativeTie) {
      addNamed(motionBetween(best.pose, c), model, out);
    }
  }
}

/// A shape alternative whose samples land this close to the surface on average (a share of the
/// sampling radius) maps the shape onto itself up to the sampling: a box's half turn about its
/// height (0.11-0.19 on the catalogue's), a can's turns (0.03-0.10); a near-square box's quarter
/// turn 0.33, a mug's turns 0.42 and more.
constexpr float kExactShift = 0.3f;

/// Where no candidate has colour evidence (a frame or a model without colour), the shape is all
/// the data can show, and a turn that maps it onto itself fits as well by construction, however
/// the refinement of its candidate went (ICP can drift a turn along a face that barely constrains
/// it): adds to `out` every such alternative of `alternatives`, as a motion from the pose.
void addExactTurns(const std::vector<Candidate>& candidates,
                   const std::vector<const ShapeAlternative*>& alternatives,
                   const PreparedModel& model, std::vector<ShapeAlternative>& out) {
  const bool colour = std::any_of(candidates.begin(), candidates.end(),
                                  [](const Candidate& c) { return c.colour.evidence; });
  if (colour) return;
  for (const ShapeAlternative* a : alternatives) {
    if (a->shift < kExactShift * model.model.sampling_radius) addNamed(*a, model, out);
  }
}

/// The turns between a lathe's steps that are judged, as a share of the step either way.
constexpr float kBetweenSteps = 2.0f / 3.0f;

/// Whether the model is a lathe whose turns between steps are not declared symmetries (a bowl's
/// are equivalents, never named).
bool turnsBetweenSteps(const PreparedModel& model) {
  if (!model.lathe) return false;
  const Eigen::Isometry3f turn = model.lathe->turn(kBetweenSteps * model.lathe->step);
  return !isSymmetry(turn, model.symmetries, sampleCentre(model.model), kSymmetryAngle,
                     model.model.sampling_radius);
}

/// Names in `instance` the turns of `best` about `lathe`'s axis by kBetweenSteps of its step either
/// way that fit as well as it (a handle straight behind the body stays hidden over a range of
/// turns), judged beside it and `first`, the instance before the choice (the fit's reference).
void addTurnsBetweenSteps(InstancePose& instance, const Candidate& first, const Candidate& best,
                          const LatheAxis& lathe, const PreparedModel& model,
                          const CandidateMeasure& measure, const ConfirmedSurface& surface,
                          const Plane* support, int threads) {
  const float angle = kBetweenSteps * lathe.step;
  std::vector<Candidate> turns{first, best, Candidate(best.pose * lathe.turn(angle), lathe.shift),
                               Candidate(best.pose * lathe.turn(-angle), lathe.shift)};
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
  for (size_t k = 2; k < turns.size(); ++k) {
    measure(turns[k], instance.region, support);
  }
  markUnsupported(turns);
  for (size_t k = 2; k < turns.size(); ++k) {
    if (fits(turns[k], first)) turns[k].left_out = measure.leftOut(turns[k], surface);
  }
  judge(turns);
  addEquallyFitting(turns, turns[1], model, instance.ambiguous);
}

/// Whether the model is a lathe whose samples' centre lies off the middle of its length along the
/// axis by more than the sampling radius: one end open, the other closed (a mug), so its turns end
/// over end, which are about that centre, come out off along the axis, where ICP barely moves them.
bool endsDiffer(const PreparedModel& model) {
  if (!model.lathe) return false;
  const Eigen::Vector3f& axis = model.lathe->axis;
  float low = std::numeric_limits<float>::infinity(), high = -low;
  for (const Eigen::Vector3f& p : model.model.points) {
    low = std::min(low, axis.dot(p));
    high = std::max(high, axis.dot(p));
  }
  const float off = axis.dot(sampleCentre(model.model)) - (low + high) / 2;
  return std::abs(off) > model.model.sampling_radius;
}

/// Judges `candidates` (the instance first), with the share of the confirmed surface each leaves
/// out; returns that surface.
ConfirmedSurface judgeAll(std::vector<Candidate>& candidates, const CandidateMeasure& measure,
                          int threads) {
  markUnsupported(candidates);
  ConfirmedSurface surface = measure.confirmedSurface(candidates);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
  for (size_t k = 0; k < candidates.size(); ++k) {
    Candidate& c = candidates[k];
    if (fits(c, candidates.front())) c.left_out = measure.leftOut(c, surface);  // else judged -1
  }
  judge(candidates);
  return surface;
}

/// Candidates judged within this of the best are slid along a lathe's axis before the choice.
constexpr float kSlideMargin = 0.1f;

/// ICP barely feels a lathe's body slide along its axis, so a turn end over end (about the samples'
/// centre, not the object's) can stop with an end in free space that a few millimetres along the
/// axis would leave, and the free share differs by a few hundredths between places a millimetre
/// apart: the candidates that fit and are judged near the best (kSlideMargin) are each moved along
/// `axis` (model frame) to their best-ranked place, so all are compared at their best. Whether any
/// moved.
bool slideNearBest(std::vector<Candidate>& candidates, const Eigen::Vector3f& axis,
                   const CandidateMeasure& measure, int region, const Plane* support, int threads) {
  float best = -std::numeric_limits<float>::infinity();
  for (const Candidate& c : candidates) best = std::max(best, c.judgement);
  std::vector<char> near(candidates.size());
  for (size_t k = 0; k < candidates.size(); ++k) {
    near[k] =
        fits(candidates[k], candidates.front()) && candidates[k].judgement >= best - kSlideMargin;
  }
  bool moved = false;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) reduction(|| : moved)
  for (size_t k = 0; k < candidates.size(); ++k) {
    if (near[k]) moved = measure.slide(candidates[k], axis, region, support) || moved;
  }
  return moved;
}

/// Chooses among `instance` and its `alternatives`; a lathe's turns between its steps are judged
/// about `lathe` (null: none), and candidates are slid along `axis` (null: none; slideNearBest).
void chooseFor(InstancePose& instance, const PreparedModel& model,
               const std::vector<const ShapeAlternative*>& alternatives, const LatheAxis* lathe,
               const Eigen::Vector3f* axis, const RefinementContext& context,
               const CandidateMeasure& measure, const PoseProximity& proximity, int threads,
               long& steps) {
  std::vector<Candidate> candidates{Candidate(instance.pose)};
  for (const ShapeAlternative* a : alternatives) {
    candidates.emplace_back(instance.pose * a->motion, a->shift);
  }
  // The alternatives take the screening steps of the instance's own candidates (those that come
  // onto another candidate on the way are dropped); the one kept, the rest of them. 0 is refined.
  const int screening = context.icp ? firstSteps(context.icp->params(), candidates.size()) : 0;
  long taken = 0;
  for (const int until : {std::min(kFirstLook, screening), screening}) {
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) reduction(+ : taken)
    for (size_t k = 1; k < candidates.size(); ++k) {
      refine(candidates[k], instance.region, until, context, taken);
    }
    dropRepeats(candidates, proximity, context.model.sampling_radius);
  }
  const std::optional<Plane> plane = measure.supportUnder(instance.pose);
  const Plane* support = plane ? &*plane : nullptr;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
  for (size_t k = 0; k < candidates.size(); ++k) measure(candidates[k], instance.region, support);

  ConfirmedSurface surface = judgeAll(candidates, measure, threads);
  if (axis && slideNearBest(candidates, *axis, measure, instance.region, support, threads)) {
    surface = judgeAll(candidates, measure, threads);
  }
  size_t kept = chosen(candidates);
  // The kept turn as judged beside the others, which have had only the screening steps: those
  // within the tie of it there fit as well, whatever its own last steps add.
  float screened = std::numeric_limits<float>::infinity();
  if (kept > 0 && context.icp) {
    screened = withoutSupport(candidates[kept]);
    // The rest of the steps can take it elsewhere (into free space): judged again there, it must
    // still be better than the instance.
    Candidate& turn = candidates[kept];
    refine(turn, instance.region, context.icp->params().iterations, context, taken);
    measure(turn, instance.region, support);
    if (axis) measure.slide(turn, *axis, instance.region, support);
    markUnsupported(candidates);
    turn.left_out = measure.leftOut(turn, surface);
    judge(candidates);
    if (turn.judgement <= candidates.front().judgement) {
      kept = 0;
      screened = std::numeric_limits<float>::infinity();  // the instance is judged as it is
    }
  }
  steps += taken;
  const Candidate& best = candidates[kept];
  instance.ambiguous.clear();
  addEquallyFitting(candidates, best, model, instance.ambiguous, screened);
  addExactTurns(candidates, alternatives, model, instance.ambiguous);
  if (lathe) {
    addTurnsBetweenSteps(instance, candidates.front(), best, *lathe, model, measure, surface,
                         support, threads);
  }
  const bool turned = kept > 0;  // an alternative, not the instance itself
  if (turned) {
    instance.pose = best.refined;
    instance.lcp = best.refined.isApprox(best.pose)
                       ? best.lcp
                       : context.scorer.detail(context.model, best.refined, instance.region);
    instance.score = instance.lcp.score;
    instance.refined = true;
  }
  if (turned || !instance.ambiguous.empty()) {
    std::vector<NearSymmetry> spread = context.near_symmetries;
    for (const ShapeAlternative& a : instance.ambiguous)
      spread.push_back({a.axis, a.angle, a.shift});
    instance.covariance = poseCovariance(context.model, context.icp, instance.pose, instance.region,
                                         &context.scorer, spread);
  }
}

}  // namespace

void chooseAmongAlternatives(std::vector<InstancePose>& instances, const PreparedModel& model,
                             const SoftSegment& segment, const RefinementContext& context,
                             const FrameEvidence& evidence, int threads, long& steps) {
  const std::vector<const ShapeAlternative*> alternatives = distinctAlternatives(model);
  if (alternatives.empty()) return;
  const CandidateMeasure measure(segment, context, evidence);
  const LatheAxis* lathe = turnsBetweenSteps(model) ? &*model.lathe : nullptr;
  const Eigen::Vector3f* axis = endsDiffer(model) ? &model.lathe->axis : nullptr;
  const PoseProximity proximity(model.model);
  for (InstancePose& instance : instances) {
    chooseFor(instance, model, alternatives, lathe, axis, context, measure, proximity, threads,
              steps);
  }
}

}  // namespace stocs
