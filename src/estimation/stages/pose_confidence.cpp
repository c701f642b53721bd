#include "stocs/estimation/stages/pose_confidence.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "stocs/estimation/pose_estimate.h"

namespace stocs {
namespace {

/// "surface_confirmed" -> "surface confirmed", for messages.
std::string spoken(const char* name) {
  std::string s = name;
  std::replace(s.begin(), s.end(), '_', ' ');
  return s;
}

/// Log-odds of a share, softened so that 0 and 1 stay finite: a share within a few percent of
/// either end counts about as much as the end itself.
double logOdds(double share) {
  constexpr double kSoftening = 0.05;
  const double x = std::clamp(share, 0.0, 1.0);
  return std::log((x + kSoftening) / (1 - x + kSoftening));
}

/// Which features enter the model as log-odds (the shares measured against the data).
constexpr std::array<bool, ConfidenceEvidence::kCount> kLogOdds = {true, true,  true,
                                                                   true, false, true};

Eigen::Matrix<double, ConfidenceEvidence::kCount, 1> termsOf(
    const Eigen::Matrix<double, ConfidenceEvidence::kCount, 1>& f) {
  Eigen::Matrix<double, ConfidenceEvidence::kCount, 1> t;
  for (int i = 0; i < ConfidenceEvidence::kCount; ++i) t[i] = kLogOdds[i] ? logOdds(f[i]) : f[i];
  return t;
}

}  // namespace

const std::array<const char*, ConfidenceEvidence::kCount>& ConfidenceEvidence::names() {
  static const std::array<const char*, kCount> names = {
      "surface_confirmed", "free_space", "map_support", "matched", "consensus", "explained"};
  return names;
}

Eigen::Matrix<double, ConfidenceEvidence::kCount, 1> ConfidenceEvidence::features() const {
  Eigen::Matrix<double, kCount, 1> f;
  f << surface_confirmed, free_space, map_support, matched, consensus, explained;
  return f;
}

ConfidenceEvidence ConfidenceEvidence::fromFeatures(const Eigen::Matrix<double, kCount, 1>& f) {
  const Eigen::Matrix<float, kCount, 1> v = f.cast<float>();
  return {v[0], v[1], v[2], v[3], v[4], v[5]};
}

Eigen::Matrix<double, ConfidenceEvidence::kCount, 1> ConfidenceEvidence::terms() const {
  return termsOf(features());
}

Eigen::Matrix<double, ConfidenceEvidence::kCount, 1> ConfidenceEvidence::limitTerms(bool best) {
  return termsOf(Eigen::Matrix<double, kCount, 1>::Constant(best ? 1.0 : 0.0));
}

/// A coefficient of the logistic model: its field, key and meaning.
struct Coefficient {
  float ConfidenceModel::*field;
  const char* key;
  const char* meaning;
};

constexpr Coefficient kCoefficients[] = {
    {&ConfidenceModel::intercept, "intercept",
     "logistic model (stocs calibrate): confidence = sigmoid(intercept + w . terms), terms: "
     "log-odds of the shares, consensus as it is"},
    {&ConfidenceModel::surface_confirmed, "surface_confirmed",
     "weight: share of the visible model surface confirmed by measured depth"},
    {&ConfidenceModel::free_space, "free_space",
     "weight: share of the visible model surface in front of measured depth"},
    {&ConfidenceModel::map_support, "map_support",
     "weight: mean network probability at the confirmed surface"},
    {&ConfidenceModel::matched, "matched",
     "weight: share of the camera-facing model points the segment matches (LCP)"},
    {&ConfidenceModel::consensus, "consensus",
     "weight: share of the 8 best bases that agree with the pose"},
    {&ConfidenceModel::explained, "explained",
     "weight: share of the confirmed surface other poses of the frame explain"},
};

/// The coefficients' entries of a schema for S, a ConfidenceModel or a struct derived from it.
template <class S>
ParamSet<S> modelSchema() {
  ParamSet<S> schema;
  for (const Coefficient& c : kCoefficients) {
    schema.add(static_cast<float S::*>(c.field), c.key, "", ParamRange::closed(-1000, 1000),
               c.meaning);
  }
  return schema;
}

const ParamSet<ConfidenceModel>& ConfidenceModel::schema() {
  static const ParamSet<ConfidenceModel> schema = modelSchema<ConfidenceModel>();
  return schema;
}

Eigen::Matrix<double, ConfidenceEvidence::kCount, 1> ConfidenceModel::weights() const {
  Eigen::Matrix<double, ConfidenceEvidence::kCount, 1> w;
  w << surface_confirmed, free_space, map_support, matched, consensus, explained;
  return w;
}

float ConfidenceModel::confidence(const ConfidenceEvidence& evidence) const {
  const double z = intercept + weights().dot(evidence.terms());
  return static_cast<float>(1.0 / (1.0 + std::exp(-z)));
}

const ParamSet<ConfidenceParams>& ConfidenceParams::schema() {
  static const ParamSet<ConfidenceParams> schema =
      modelSchema<ConfidenceParams>()
          .nest(&ConfidenceParams::depth_alone, "depth_alone", ConfidenceModel::schema())
          .add(&ConfidenceParams::min_confidence, "min_confidence", "", ParamRange::closed(0, 1),
               "poses below this confidence are rejected (not published or written)")
          .flag("--min-confidence");
  return schema;
}

void ConfidenceParams::validate() const {
  schema().validate(*this);
}

ConfidenceParams ConfidenceParams::forDepthAloneMaps() const {
  ConfidenceParams p = *this;
  static_cast<ConfidenceModel&>(p) = depth_alone;
  return p;
}

void judgePose(InstancePose& pose, const ConfidenceParams& params) {
  pose.confidence = params.confidence(pose.evidence);
  pose.accepted = pose.confidence >= params.min_confidence;
  pose.rejection.clear();
  if (pose.accepted) return;
  // A feature's shortfall is what it costs against its best value (1 for a positive weight, 0
  // for a negative one).
  const auto f = pose.evidence.features();
  const auto t = pose.evidence.terms();
  const auto w = params.weights();
  const auto best = ConfidenceEvidence::limitTerms(true),
             worst = ConfidenceEvidence::limitTerms(false);
  std::array<int, ConfidenceEvidence::kCount> order;
  std::iota(order.begin(), order.end(), 0);
  const auto shortfall = [&](int i) { return w[i] * ((w[i] > 0 ? best[i] : worst[i]) - t[i]); };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return shortfall(a) > shortfall(b); });
  const auto& names = ConfidenceEvidence::names();
  pose.rejection =
      fmt::format("confidence {:.2f} below min_confidence {:.2f} ({} {:.2f}, {} {:.2f})",
                  pose.confidence, params.min_confidence, spoken(names[order[0]]), f[order[0]],
                  spoken(names[order[1]]), f[order[1]]);
}

}  // namespace stocs
