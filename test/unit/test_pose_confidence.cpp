// The pose confidence: the logistic model over the evidence, the verdict against min_confidence
// with a reason naming the weakest evidence, and the parameters' ranges.
#include <gtest/gtest.h>

#include <cmath>

#include "stocs/estimation/stages/pose_confidence.h"
#include "stocs/estimation/stocs_estimator.h"
#include "stocs/methods/pose_method.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

ConfidenceParams model() {
  ConfidenceParams p;
  p.intercept = -4;
  p.surface_confirmed = 6;
  p.free_space = -8;
  p.map_support = 2;
  p.matched = 1;
  p.consensus = 1;
  p.explained = -3;
  p.min_confidence = 0.5f;
  return p;
}

/// The model's term for a share: its log-odds, softened by 0.05 at both ends.
double logOdds(double share) {
  return std::log((share + 0.05) / (1 - share + 0.05));
}

TEST(PoseConfidence, IsTheLogisticOfTheWeightedTerms) {
  ConfidenceEvidence e;
  e.surface_confirmed = 0.9f;
  e.free_space = 0.05f;
  e.map_support = 0.8f;
  e.matched = 0.6f;
  e.consensus = 1;
  e.explained = 0.2f;
  // The shares enter as log-odds, consensus as it is.
  const double z = -4 + 6 * logOdds(0.9) - 8 * logOdds(0.05) + 2 * logOdds(0.8) + 1 * logOdds(0.6) +
                   1 - 3 * logOdds(0.2);
  EXPECT_NEAR(model().confidence(e), 1 / (1 + std::exp(-z)), 1e-6);
  EXPECT_EQ(ConfidenceEvidence::fromFeatures(e.features()).features(), e.features());
}

TEST(PoseConfidence, RejectsBelowTheMinimumNamingTheWeakestEvidence) {
  InstancePose pose;
  pose.evidence.surface_confirmed = 0.9f;
  pose.evidence.map_support = 0.9f;
  pose.evidence.consensus = 1;
  judgePose(pose, model());
  EXPECT_TRUE(pose.accepted);
  EXPECT_GT(pose.confidence, 0.5f);
  EXPECT_TRUE(pose.rejection.empty());

  // Against their best values, the surface in free space costs 8 * 3.8 in the logit, the
  // unconfirmed surface 6 * 4.3, the unmatched model 1 * 6.1: the first two named, free first.
  pose.evidence.surface_confirmed = 0.2f;
  pose.evidence.free_space = 0.7f;
  judgePose(pose, model());
  EXPECT_FALSE(pose.accepted);
  EXPECT_LT(pose.confidence, 0.5f);
  EXPECT_EQ(pose.rejection.rfind("confidence 0.00 below min_confidence 0.50 (", 0), 0u)
      << pose.rejection;
  EXPECT_NE(pose.rejection.find("(free space 0.70, surface confirmed 0.20)"), std::string::npos)
      << pose.rejection;

  // min_confidence 0 accepts every pose.
  ConfidenceParams all = model();
  all.min_confidence = 0;
  judgePose(pose, all);
  EXPECT_TRUE(pose.accepted);
}

TEST(PoseConfidence, ParametersOutOfRangeAreRefused) {
  ConfidenceParams p = model();
  p.min_confidence = 1.5f;
  EXPECT_THROW(p.validate(), InputError);
  p = model();
  p.free_space = NAN;
  EXPECT_THROW(p.validate(), InputError);
  EXPECT_NO_THROW(model().validate());
}

TEST(PoseConfidence, OnlyStocsMethodsGiveOne) {
  // The CLI writes the confidence as the score of these, a baseline's own score otherwise.
  for (const std::string& name : methodNames()) {
    EXPECT_EQ(makeMethod(name)->givesConfidence(), name.rfind("stocs", 0) == 0) << name;
  }
}

}  // namespace
}  // namespace stocs
