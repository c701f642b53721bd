// The alignment objective f of the paper on a hand-made case.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>

#include "stocs/estimation/stages/lcp_scorer.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

// Segment: s0 and s2 face the camera; s1 is 3 mm from s0 with a sideways normal.
SoftSegment handMadeSegment() {
  SoftSegment s;
  s.points = {{0, 0, 1}, {0.003f, 0, 1}, {0.1f, 0, 1}};
  s.normals = {{0, 0, -1}, {1, 0, 0}, {0, 0, -1}};
  s.probability = {0.5f, 0.3f, 0.2f};
  s.confidence = {0.9f, 0.5f, 0.4f};
  s.pixel = {0, 1, 2};
  return s;
}

// Model (identity pose):
//   m0 1 mm from s0, normal agrees               -> pi(s0) = 0.5
//   m1 closest to s1 (0.2 mm), normal disagrees   -> 0, although s0 is within delta_s and agrees
//   m2 4 mm from s2, normal agrees                -> pi(s2) = 0.2
//   m3 6 mm from s2: beyond delta_s = 5 mm        -> 0
//   m4 at s0, normal facing away                  -> 0
ObjectModel handMadeModel() {
  ObjectModel m;
  m.points = {
      {0.001f, 0, 1}, {0.0028f, 0, 1}, {0.1f, 0, 1.004f}, {0.1f, 0, 1.006f}, {0, 0.001f, 1}};
  m.normals = {{0, 0, -1}, {0, 0, -1}, {0, 0, -1}, {0, 0, -1}, {0, 0, 1}};
  m.diameter = 0.1f;
  return m;
}

TEST(LcpScorer, HandMadeCaseMatchesThePaperObjective) {
  const SoftSegment segment = handMadeSegment();
  const LcpScorer scorer(segment, LcpParams{});
  const ObjectModel model = handMadeModel();
  EXPECT_FLOAT_EQ(scorer.score(model, Eigen::Isometry3f::Identity()), 0.7f);
  const LcpDetail d = scorer.detail(model, Eigen::Isometry3f::Identity());
  EXPECT_FLOAT_EQ(d.score, 0.7f);
  EXPECT_EQ(d.matched, 2);
  EXPECT_EQ(d.facing, 4);
  EXPECT_FLOAT_EQ(d.mean_confidence, (0.9f + 0.4f) / 2);
}

TEST(LcpScorer, ThePoseMovesTheModel) {
  const SoftSegment segment = handMadeSegment();
  const LcpScorer scorer(segment, LcpParams{});
  ObjectModel moved = handMadeModel();
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.linear() =
      Eigen::AngleAxisf(0.8f, Eigen::Vector3f(0.3f, 1, 0.2f).normalized()).toRotationMatrix();
  pose.translation() = Eigen::Vector3f(0.05f, -0.02f, 0.1f);
  for (size_t i = 0; i < moved.size(); ++i) {  // model expressed so that `pose` puts it back
    moved.points[i] = pose.inverse() * moved.points[i];
    moved.normals[i] = pose.linear().transpose() * moved.normals[i];
  }
  EXPECT_NEAR(scorer.score(moved, pose), 0.7f, 1e-6f);
  EXPECT_FLOAT_EQ(scorer.score(moved, Eigen::Isometry3f::Identity()), 0.0f);
}

TEST(LcpScorer, ThresholdsAreParameters) {
  const SoftSegment segment = handMadeSegment();
  LcpParams wide;
  wide.distance = 0.0065f;  // m3 now reaches s2
  EXPECT_FLOAT_EQ(LcpScorer(segment, wide).score(handMadeModel(), Eigen::Isometry3f::Identity()),
                  0.9f);
  LcpParams lax;
  lax.normal_angle_deg = 91;  // s1's sideways normal is 90 degrees from m1's
  EXPECT_FLOAT_EQ(LcpScorer(segment, lax).score(handMadeModel(), Eigen::Isometry3f::Identity()),
                  1.0f);
}

TEST(LcpScorer, EarlyStopOnlyWhenTheTargetIsOutOfReach) {
  const SoftSegment segment = handMadeSegment();
  const LcpScorer scorer(segment, LcpParams{});
  const ObjectModel model = handMadeModel();
  EXPECT_FLOAT_EQ(scorer.score(model, Eigen::Isometry3f::Identity(), -1, 0.7f), 0.7f);
  EXPECT_LT(scorer.score(model, Eigen::Isometry3f::Identity(), -1, 10.0f), 0.0f);
}

TEST(LcpScorer, RegionsRestrictTheClosestPointSearch) {
  SoftSegment segment = handMadeSegment();
  segment.region = {1, 2, 1};
  const LcpScorer scorer(segment, LcpParams{});
  const ObjectModel model = handMadeModel();
  // Region 1 holds s0 and s2: m1's closest point is now s0 (2.8 mm, normal agrees).
  EXPECT_FLOAT_EQ(scorer.score(model, Eigen::Isometry3f::Identity(), 1), 0.5f + 0.5f + 0.2f);
  // Region 2 holds only s1, whose normal agrees with no model point.
  EXPECT_FLOAT_EQ(scorer.score(model, Eigen::Isometry3f::Identity(), 2), 0.0f);
  // Region -1 still means every point (its grid is built on first use when there are regions).
  const SoftSegment whole = handMadeSegment();
  const LcpScorer plain(whole, LcpParams{});
  EXPECT_FLOAT_EQ(scorer.score(model, Eigen::Isometry3f::Identity(), -1),
                  plain.score(model, Eigen::Isometry3f::Identity(), -1));
  EXPECT_EQ(scorer.closest(segment.points[1], -1), 1);
}

// A flat patch of model points in random order, half of them over the segment, and one segment
// point far away with probability 1 so that the exact bound stays loose until the very end.
struct HalfCoveredPatch {
  SoftSegment segment;
  ObjectModel model;
  HalfCoveredPatch() {
    for (int i = 0; i < 40; ++i) {
      for (int j = 0; j < 40; ++j) {
        const Eigen::Vector3f p(0.002f * i, 0.002f * j, 1.0f);
        model.points.push_back(p);
        model.normals.emplace_back(0, 0, -1);
        if (i < 20) addSegmentPoint(p, 1.0f / 800);
      }
    }
    addSegmentPoint({0.5f, 0, 1}, 1.0f);
    std::vector<size_t> order(model.points.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::shuffle(order.begin(), order.end(), std::mt19937(7));
    const ObjectModel grid = model;
    for (size_t k = 0; k < order.size(); ++k) {
      model.points[k] = grid.points[order[k]];
      model.normals[k] = grid.normals[order[k]];
    }
    model.diameter = 0.11f;
  }
  void addSegmentPoint(const Eigen::Vector3f& p, float probability) {
    segment.points.push_back(p);
    segment.normals.emplace_back(0, 0, -1);
    segment.probability.push_back(probability);
    segment.confidence.push_back(probability);
    segment.pixel.push_back(static_cast<int>(segment.pixel.size()));
  }
};

TEST(LcpScorer, CoarseCheckDropsOnlyHypothesesFarBelowTheTarget) {
  const HalfCoveredPatch patch;
  const LcpScorer scorer(patch.segment, LcpParams{});
  const Eigen::Isometry3f id = Eigen::Isometry3f::Identity();
  const float full = scorer.detail(patch.model, id).score;
  // 800 model points over the segment and the 2 columns within delta_s of its edge match.
  ASSERT_NEAR(full, 880.0f / 800, 1e-4f);
  // After an eighth of the model (about 0.14 scored) a target of 3 is far out of line: dropped,
  // although the exact bound alone, loose here, scores it in full.
  EXPECT_LT(scorer.score(patch.model, id, -1, 3.0f), 0.0f);
  LcpParams exact;
  exact.coarse_fraction = 0;
  EXPECT_NEAR(LcpScorer(patch.segment, exact).score(patch.model, id, -1, 3.0f), full, 1e-4f);
  // A hypothesis that reaches its target is scored in full.
  EXPECT_NEAR(scorer.score(patch.model, id, -1, 0.95f * full), full, 1e-4f);
}

TEST(LcpScorer, LaterCoarseChecksAllowLessMargin) {
  const HalfCoveredPatch patch;
  const LcpScorer scorer(patch.segment, LcpParams{});
  const Eigen::Isometry3f id = Eigen::Isometry3f::Identity();
  const float full = scorer.detail(patch.model, id).score;
  // A target of 2: the first eighth extrapolates to about 1.1, above half of it, so the first
  // check keeps the hypothesis; the second check (a quarter seen) allows a margin of only
  // 0.5 * sqrt(3/7) = 0.33 below the target and drops it.
  PartialScore head;
  scorer.extendHead(patch.model, id, -1, head, 1.0f);
  ASSERT_GT(head.total * 1600 / head.seen, 0.5f * 2.0f);
  EXPECT_LT(scorer.score(patch.model, id, -1, 2.0f), 0.0f);
  // At 7/8 seen the margin is 0.5 * sqrt(1/49) = 0.07: a target 10% above the final score drops
  // the hypothesis before its end, where the exact bound (loose here) would not.
  EXPECT_LT(scorer.score(patch.model, id, -1, 1.1f * full), 0.0f);
  LcpParams exact;
  exact.coarse_fraction = 0;
  EXPECT_NEAR(LcpScorer(patch.segment, exact).score(patch.model, id, -1, 1.1f * full), full, 1e-4f);
}

TEST(LcpScorer, HeadThenFinishIsTheWholeScore) {
  const HalfCoveredPatch patch;
  const LcpScorer scorer(patch.segment, LcpParams{});
  const Eigen::Isometry3f id = Eigen::Isometry3f::Identity();
  PartialScore head;
  scorer.extendHead(patch.model, id, -1, head, 1.0f);
  // The head is the first coarse_fraction of the model (1600 / 8 = 200) in whole chunks of 16.
  EXPECT_EQ(head.seen, 208u);
  const float full = scorer.detail(patch.model, id).score;
  EXPECT_NEAR(head.total * 1600 / head.seen, full, 0.3f * full);  // an unbiased sample
  for (float target : {-std::numeric_limits<float>::infinity(), 1.0f, 1.2f, 2.0f, 3.0f}) {
    EXPECT_EQ(scorer.finishScore(patch.model, id, -1, head, target),
              scorer.score(patch.model, id, -1, target))
        << "target " << target;
  }
}

TEST(LcpScorer, InvalidThresholdsAreRejected) {
  const SoftSegment segment = handMadeSegment();
  LcpParams bad;
  bad.distance = 0;
  EXPECT_THROW(LcpScorer(segment, bad), InputError);
  bad = LcpParams{};
  bad.normal_angle_deg = 200;
  EXPECT_THROW(LcpScorer(segment, bad), InputError);
}

}  // namespace
}  // namespace stocs
