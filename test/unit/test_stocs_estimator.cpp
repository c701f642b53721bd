// The whole pipeline on a rendered scene with a known pose: accuracy, determinism, budgets and
// degenerate inputs.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "stocs/estimation/pipeline.h"
#include "stocs/estimation/stages/icp_refiner.h"
#include "stocs/eval/pose_metrics.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

class StocsEstimatorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    camera_ = test::testCamera();
    truth_ = test::viewingPose(0.6f);
    Eigen::Isometry3f table = Eigen::Isometry3f::Identity();
    table.translation() = Eigen::Vector3f(0, 0, 0.68f);
    cv::Mat labels;
    const cv::Mat depth = test::renderDepth(
        {{asymmetricMesh(), truth_}, {boxMesh({0.5f, 0.4f, 0.01f}), table}}, camera_, &labels);
    cloud_ = cloudFromDepth(depth, camera_, 1.0);
    // A soft segmentation that bleeds onto the table with a moderate probability.
    probability_ = cv::Mat(240, 320, CV_32FC1, cv::Scalar(0));
    for (int v = 0; v < 240; ++v) {
      for (int u = 0; u < 320; ++u) {
        const int l = labels.at<int>(v, u);
        probability_.at<float>(v, u) =
            l == 1 ? 0.9f
                   : (l == 2 && std::abs(u - 170) < 70 && std::abs(v - 120) < 60 ? 0.3f : 0.0f);
      }
    }
    model_.model = prepareModel(asymmetricMesh(), ModelSamplingParams{});
    model_.ppf_map = PpfHashMap::build(model_.model, PpfParams{});
  }

  /// The whole pipeline (soft segment, estimate) on the rendered frame.
  PoseEstimate estimate(const PipelineParams& params) const {
    return detectObject(cloud_, static_cast<float>(camera_.fx), probability_, model_, params);
  }

  SoftSegment segment(const PipelineParams& params) const {
    return buildSoftSegment(cloud_, probability_, static_cast<float>(camera_.fx), params.segment);
  }

  double addsOf(const PoseEstimate& e) const {
    return addsError(
        model_.model.points,
        {e.best().pose.linear().cast<double>(), e.best().pose.translation().cast<double>()},
        {truth_.linear().cast<double>(), truth_.translation().cast<double>()});
  }

  CameraIntrinsics camera_;
  Eigen::Isometry3f truth_;
  OrganizedCloud cloud_;
  cv::Mat probability_;
  PreparedModel model_;
};

TEST_F(StocsEstimatorTest, FindsTheRenderedPose) {
  PipelineParams params;
  for (uint64_t seed : {1u, 2u, 3u}) {
    params.stocs.seed = seed;
    const PoseEstimate r = estimate(params);
    ASSERT_TRUE(r.found()) << "seed " << seed;
    EXPECT_GT(r.segment_points, 100u);
    EXPECT_LT(addsOf(r), 0.05 * model_.model.diameter) << "seed " << seed;
    // The asymmetric block makes the pose unique: ADD (no symmetry forgiveness) is small too.
    EXPECT_LT(addError(model_.model.points,
                       {r.best().pose.linear().cast<double>(),
                        r.best().pose.translation().cast<double>()},
                       {truth_.linear().cast<double>(), truth_.translation().cast<double>()}),
              0.05 * model_.model.diameter);
    // The loop runs whole blocks of bases until its consensus stop, at most every base.
    EXPECT_LE(r.bases_tried, params.stocs.bases);
    EXPECT_EQ(r.bases_tried % StocsParams::kConsensusBlock, 0);
    EXPECT_GT(r.hypotheses, 0);
    EXPECT_GT(r.best().lcp.matched, 50);
  }
}

TEST_F(StocsEstimatorTest, FitsThatTurnTheModelOverAreNotScored) {
  PipelineParams params;
  params.stocs.seed = 5;
  params.stocs.min_normal_agreement = 0;
  const PoseEstimate all = estimate(params);
  params.stocs.min_normal_agreement = 1;
  const PoseEstimate agreeing = estimate(params);
  EXPECT_EQ(all.normal_mismatches, 0);
  // The block's flat faces give fits with every normal reversed; they are skipped, and the pose
  // found is as good.
  EXPECT_GT(agreeing.normal_mismatches, 0);
  EXPECT_LT(agreeing.hypotheses, all.hypotheses);
  ASSERT_TRUE(agreeing.found());
  EXPECT_LT(addsOf(agreeing), 0.05 * model_.model.diameter);
}

TEST_F(StocsEstimatorTest, OnlyTheBestHeadsOfABaseAreFinished) {
  PipelineParams params;
  params.stocs.seed = 5;
  params.stocs.finished_per_base = 100000;
  const PoseEstimate every = estimate(params);
  params.stocs.finished_per_base = 2;
  const PoseEstimate best_two = estimate(params);
  EXPECT_EQ(every.finished, every.hypotheses);
  EXPECT_LE(best_two.finished, 2L * best_two.bases_with_sets);
  EXPECT_LT(best_two.finished, every.finished);
  ASSERT_TRUE(best_two.found());
  EXPECT_LT(addsOf(best_two), 0.05 * model_.model.diameter);
}

TEST_F(StocsEstimatorTest, SameSeedSameResultForAnyThreadCount) {
  PipelineParams params;
  params.stocs.seed = 42;
  params.stocs.threads = 1;
  const PoseEstimate one = StocsEstimator(model_, params.stocs).search(segment(params));
  params.stocs.threads = 2;
  const PoseEstimate two = StocsEstimator(model_, params.stocs).search(segment(params));
  const PoseEstimate again = StocsEstimator(model_, params.stocs).search(segment(params));
  ASSERT_TRUE(one.found());
  EXPECT_EQ(one.best().pose.matrix(), two.best().pose.matrix());
  EXPECT_EQ(two.best().pose.matrix(), again.best().pose.matrix());
  EXPECT_EQ(one.best().lcp.score, two.best().lcp.score);
  EXPECT_EQ(one.hypotheses, two.hypotheses);
}

// With no more bases than ICP candidates, threads out of bases begin the refinements of finished
// bases. One thread begins them all after its bases; with more threads than bases the idle ones
// find nothing finished at first and leave them all to the refinement after the loop. Both give
// the same answer, with and without screening (2 bases: no more candidates than finalists).
TEST_F(StocsEstimatorTest, RefinementsBegunDuringTheBaseLoopChangeNothing) {
  PipelineParams params;
  params.stocs.seed = 5;
  // One screening step: on this clean scene refinements converge within a few steps, and a
  // candidate that took more than its screening steps would go unnoticed.
  params.stocs.icp.screening_iterations = 1;
  const SoftSegment seg = segment(params);
  for (int bases : {2, 3, 5}) {
    params.stocs.bases = bases;
    params.stocs.threads = 1;
    const PoseEstimate one = StocsEstimator(model_, params.stocs).search(seg);
    ASSERT_TRUE(one.found()) << bases;
    EXPECT_TRUE(one.best().refined) << bases;
    EXPECT_GT(one.icp_steps, 0) << bases;
    for (int threads : {2, 3, 8}) {
      params.stocs.threads = threads;
      const PoseEstimate many = StocsEstimator(model_, params.stocs).search(seg);
      EXPECT_EQ(many.best().pose.matrix(), one.best().pose.matrix())
          << bases << " bases, " << threads;
      EXPECT_EQ(many.best().lcp.score, one.best().lcp.score) << bases << " bases, " << threads;
      // The same steps: begun early, a candidate still takes only the screening steps unless it
      // is a finalist.
      EXPECT_EQ(many.icp_steps, one.icp_steps) << bases << " bases, " << threads;
    }
  }
}

TEST_F(StocsEstimatorTest, RefinementMovesTowardTheTruthAndKeepsTheObjective) {
  PipelineParams params;
  params.stocs.seed = 7;
  const PoseEstimate refined = StocsEstimator(model_, params.stocs).search(segment(params));
  params.stocs.icp.enabled = false;
  const PoseEstimate raw = StocsEstimator(model_, params.stocs).search(segment(params));
  ASSERT_TRUE(refined.found() && raw.found());
  EXPECT_TRUE(refined.best().refined);
  EXPECT_FALSE(raw.best().refined);
  EXPECT_GE(refined.best().lcp.score, 0.9f * raw.best().lcp.score);  // the divergence guard
  EXPECT_LE(addsOf(refined), addsOf(raw) + 1e-4);  // and it moves toward the truth
}

TEST_F(StocsEstimatorTest, IcpThroughTheScorersGridRefinesExactlyAsWithoutIt) {
  const PipelineParams params;
  const SoftSegment seg = segment(params);
  const IcpRefiner icp(seg, params.stocs.icp);
  // A start a few millimetres and degrees off: most correspondences lie within delta_s, some
  // beyond it.
  Eigen::Isometry3f start = truth_;
  start.rotate(Eigen::AngleAxisf(0.05f, Eigen::Vector3f(1, 2, 3).normalized()));
  start.pretranslate(Eigen::Vector3f(0.004f, -0.003f, 0.002f));
  const Eigen::Isometry3f alone = icp.refine(model_.model, start, -1);
  ASSERT_FALSE(alone.isApprox(start));
  const LcpScorer near(seg, params.stocs.lcp);
  EXPECT_EQ(icp.refine(model_.model, start, -1, &near).matrix(), alone.matrix());
  // A scorer whose delta_s exceeds the correspondence radius would admit farther points: ignored.
  LcpParams wide = params.stocs.lcp;
  wide.distance = 2.5f * params.stocs.icp.max_distance;
  const LcpScorer too_wide(seg, wide);
  EXPECT_EQ(icp.refine(model_.model, start, -1, &too_wide).matrix(), alone.matrix());
}

// Screening refines every candidate a few steps and only the finalists to the end: with no more
// candidates than finalists it changes nothing, and with more it still finds the pose.
TEST_F(StocsEstimatorTest, IcpScreeningKeepsTheFinalists) {
  PipelineParams params;
  params.stocs.seed = 3;
  params.stocs.consensus_bases = 0;  // every base: all 10 candidates
  const SoftSegment seg = segment(params);
  params.stocs.icp.screening_iterations = 0;
  const PoseEstimate full = StocsEstimator(model_, params.stocs).search(seg);
  params.stocs.icp.screening_iterations = 8;
  params.stocs.icp.finalists = params.stocs.icp.candidates;
  const PoseEstimate all_finalists = StocsEstimator(model_, params.stocs).search(seg);
  params.stocs.icp.finalists = 2;
  const PoseEstimate screened = StocsEstimator(model_, params.stocs).search(seg);
  ASSERT_TRUE(full.found() && all_finalists.found() && screened.found());
  EXPECT_EQ(all_finalists.best().pose.matrix(), full.best().pose.matrix());
  EXPECT_LT(addsOf(screened), 0.05 * model_.model.diameter);
  EXPECT_TRUE(screened.best().refined);

  // Several instances: every candidate may be one, and each is refined to the end (one screening
  // step would leave the candidates that are not finalists a step from their start).
  params.stocs.instances = 3;
  params.stocs.icp.screening_iterations = 1;
  const PoseEstimate several = StocsEstimator(model_, params.stocs).search(seg);
  params.stocs.icp.screening_iterations = 0;
  const PoseEstimate several_full = StocsEstimator(model_, params.stocs).search(seg);
  ASSERT_EQ(several.instances.size(), several_full.instances.size());
  for (size_t k = 0; k < several.instances.size(); ++k) {
    EXPECT_EQ(several.instances[k].pose.matrix(), several_full.instances[k].pose.matrix()) << k;
  }
}

TEST_F(StocsEstimatorTest, ATimeBudgetStopsTheLoop) {
  PipelineParams params;
  params.stocs.bases = 100000;
  params.stocs.consensus_bases = 0;  // the budget alone ends the loop
  params.stocs.time_budget = 0.05;
  const PoseEstimate e = StocsEstimator(model_, params.stocs).search(segment(params));
  EXPECT_LT(e.bases_tried, 100000);
  EXPECT_LT(e.seconds, 5.0);  // generous: the loop stops starting bases after 50 ms
}

TEST_F(StocsEstimatorTest, ConsensusEndsTheLoopEarlyWithTheSameAnswerOnAnyThreadCount) {
  PipelineParams params;  // the default consensus
  for (uint64_t seed : {1u, 2u, 3u}) {
    params.stocs.seed = seed;
    params.stocs.threads = 1;
    const PoseEstimate one = StocsEstimator(model_, params.stocs).search(segment(params));
    params.stocs.threads = 2;
    const PoseEstimate two = StocsEstimator(model_, params.stocs).search(segment(params));
    ASSERT_TRUE(one.found()) << "seed " << seed;
    // The block is plainly visible: its bases agree long before the hundredth, and the loop ends
    // between whole blocks of bases.
    EXPECT_LT(one.bases_tried, params.stocs.bases) << "seed " << seed;
    EXPECT_EQ(one.bases_tried % StocsParams::kConsensusBlock, 0) << "seed " << seed;
    EXPECT_LT(addsOf(one), 0.05 * model_.model.diameter) << "seed " << seed;
    EXPECT_EQ(one.bases_tried, two.bases_tried) << "seed " << seed;
    EXPECT_EQ(one.best().pose.matrix(), two.best().pose.matrix()) << "seed " << seed;
  }
}

TEST_F(StocsEstimatorTest, ConsensusNeverStopsASearchForSeveralInstances) {
  PipelineParams params;
  params.stocs.seed = 1;
  params.stocs.consensus_bases = 1;  // the first block would always end it
  params.stocs.instances = 2;
  EXPECT_EQ(StocsEstimator(model_, params.stocs).search(segment(params)).bases_tried,
            params.stocs.bases);
  params.stocs.instances = 1;
  EXPECT_EQ(StocsEstimator(model_, params.stocs).search(segment(params)).bases_tried,
            StocsParams::kConsensusBlock);
}

TEST_F(StocsEstimatorTest, BasesWithNothingToVerifyAreDrawnAgainWithinTheBudget) {
  PipelineParams params;
  params.stocs.seed = 4;
  params.stocs.bases = 10;
  params.stocs.consensus_bases = 0;
  params.stocs.base_draw_budget = 0;  // one draw per base
  params.stocs.focused_bases = 0;     // focused draws keep off the table's low probabilities
  const SoftSegment seg = segment(params);
  const PoseEstimate once = StocsEstimator(model_, params.stocs).search(seg);
  EXPECT_EQ(once.base_draws, once.bases_sampled);
  // The segment bleeds onto the table, and some of the paper's bases straddle it and the block.
  ASSERT_LT(once.bases_with_sets, params.stocs.bases);

  params.stocs.base_draw_budget = 100;  // up to 10 draws per base
  params.stocs.threads = 1;
  const PoseEstimate again = StocsEstimator(model_, params.stocs).search(seg);
  EXPECT_GT(again.base_draws, once.base_draws);
  EXPECT_LE(again.base_draws, 10 * params.stocs.bases);
  EXPECT_GT(again.bases_with_sets, once.bases_with_sets);
  ASSERT_TRUE(again.found());
  params.stocs.threads = 2;  // the draws of a base come from its own stream
  EXPECT_EQ(StocsEstimator(model_, params.stocs).search(seg).best().pose.matrix(),
            again.best().pose.matrix());

  // With as many bases as the budget, every base is drawn once: the paper's loop.
  params.stocs.bases = 100;
  params.stocs.base_draw_budget = 100;
  const PoseEstimate full = StocsEstimator(model_, params.stocs).search(seg);
  params.stocs.base_draw_budget = 0;
  const PoseEstimate paper = StocsEstimator(model_, params.stocs).search(seg);
  EXPECT_EQ(full.base_draws, full.bases_sampled);
  EXPECT_EQ(full.best().pose.matrix(), paper.best().pose.matrix());
  EXPECT_EQ(full.hypotheses, paper.hypotheses);
}

TEST_F(StocsEstimatorTest, OnlyTheFirstBasesAreFocused) {
  PipelineParams params;
  params.stocs.seed = 6;
  params.stocs.bases = 20;
  params.stocs.consensus_bases = 0;
  const SoftSegment seg = segment(params);
  auto run = [&](int focused_bases, int exponent) {
    StocsParams p = params.stocs;
    p.focused_bases = focused_bases;
    p.base.focus_exponent = exponent;
    return StocsEstimator(model_, p).search(seg);
  };
  // No focused base and focused bases at exponent 1 are the paper's draws alike.
  const PoseEstimate paper = run(0, 1);
  const PoseEstimate unfocused = run(0, 6);
  const PoseEstimate exponent_one = run(10, 1);
  EXPECT_EQ(unfocused.hypotheses, paper.hypotheses);
  EXPECT_EQ(unfocused.best().pose.matrix(), paper.best().pose.matrix());
  EXPECT_EQ(exponent_one.hypotheses, paper.hypotheses);
  EXPECT_EQ(exponent_one.best().pose.matrix(), paper.best().pose.matrix());
  // Focusing changes the draws of the first bases only: with the first 10 focused, the last 10
  // bases are the paper's, so the hypotheses differ from both extremes.
  const PoseEstimate first = run(10, 6);
  const PoseEstimate every = run(20, 6);
  EXPECT_NE(first.hypotheses, paper.hypotheses);
  EXPECT_NE(first.hypotheses, every.hypotheses);
  EXPECT_TRUE(first.found() && every.found());
}

// A caller that knows the frame's intrinsics passes them; intrinsics of another image size are an
// input error, not a silently disabled free-space check.
TEST_F(StocsEstimatorTest, TheFramesIntrinsicsMustFitTheCloud) {
  const PipelineParams params;
  const auto focal = static_cast<float>(camera_.fx);
  const PoseEstimate recovered = detectObject(cloud_, focal, probability_, model_, params);
  const PoseEstimate given =
      detectObject(cloud_, focal, probability_, model_, params, nullptr, &camera_);
  ASSERT_TRUE(given.found());
  EXPECT_LT(addsOf(given), 0.05 * model_.model.diameter);
  EXPECT_LT(addsOf(recovered), 0.05 * model_.model.diameter);
  CameraIntrinsics other = camera_;
  other.width = camera_.width / 2;
  try {
    detectObject(cloud_, focal, probability_, model_, params, nullptr, &other);
    ADD_FAILURE() << "intrinsics of another size were accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("camera intrinsics are for 160x240 images"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(StocsEstimatorTest, EmptyOrTinySegmentsGiveNoPose) {
  PipelineParams params;
  const cv::Mat nothing(240, 320, CV_32FC1, cv::Scalar(0));
  const PoseEstimate r =
      detectObject(cloud_, static_cast<float>(camera_.fx), nothing, model_, params);
  EXPECT_EQ(r.segment_points, 0u);
  EXPECT_FALSE(r.found());
  const PoseEstimate nan_cloud = detectObject(
      OrganizedCloud(320, 240), static_cast<float>(camera_.fx), probability_, model_, params);
  EXPECT_FALSE(nan_cloud.found());
}

TEST(StocsEstimator, SeveralInstancesOfOneObjectAreReportedOnceEach) {
  const CameraIntrinsics camera = test::testCamera();
  std::vector<Eigen::Isometry3f> truths = {test::viewingPose(0.6f), test::viewingPose(0.6f)};
  truths[0].pretranslate(Eigen::Vector3f(-0.08f, 0, 0));
  truths[1].pretranslate(Eigen::Vector3f(0.08f, 0.02f, 0));
  cv::Mat labels;
  const cv::Mat depth = test::renderDepth(
      {{asymmetricMesh(), truths[0]}, {asymmetricMesh(), truths[1]}}, camera, &labels);
  cv::Mat probability;
  cv::Mat(labels > 0).convertTo(probability, CV_32FC1, 0.9 / 255);
  PreparedModel model;
  model.model = prepareModel(asymmetricMesh(), ModelSamplingParams{});
  model.ppf_map = PpfHashMap::build(model.model, PpfParams{});
  PipelineParams params;
  params.stocs.instances = 3;  // one more than there are: the third, if any, is not a duplicate
  const PoseEstimate r = detectObject(cloudFromDepth(depth, camera, 1.0),
                                      static_cast<float>(camera.fx), probability, model, params);
  ASSERT_GE(r.instances.size(), 2u);
  std::vector<int> found(truths.size(), 0);
  for (const InstancePose& p : r.instances) {
    for (size_t t = 0; t < truths.size(); ++t) {
      const double adds = addsError(
          model.model.points, {p.pose.linear().cast<double>(), p.pose.translation().cast<double>()},
          {truths[t].linear().cast<double>(), truths[t].translation().cast<double>()});
      found[t] += adds < 0.1 * model.model.diameter;
    }
  }
  EXPECT_EQ(found, (std::vector<int>{1, 1}));  // both found, neither twice
  for (size_t k = 1; k < r.instances.size(); ++k) {
    EXPECT_LE(r.instances[k].score, r.instances[k - 1].score);
  }
}

}  // namespace
}  // namespace stocs
