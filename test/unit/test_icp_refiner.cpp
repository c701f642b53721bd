// Point-to-plane ICP on a segment made of the model's own camera-facing samples, so that every
// correspondence is exact and only the step itself can go wrong.
#include <gtest/gtest.h>

#include "stocs/estimation/stages/icp_refiner.h"
#include "stocs/eval/pose_metrics.h"
#include "stocs/model/object_model.h"
#include "stocs/sim/object_catalogue.h"
#include "test_support.h"

namespace stocs {
namespace {

/// The samples of `model` at `pose` that face the camera, as a segment of uniform confidence.
SoftSegment visibleSamples(const ObjectModel& model, const Eigen::Isometry3f& pose) {
  SoftSegment segment;
  for (size_t i = 0; i < model.size(); ++i) {
    const Eigen::Vector3f p = pose * model.points[i];
    const Eigen::Vector3f n = pose.linear() * model.normals[i];
    if (n.dot(p) >= 0) continue;
    segment.points.push_back(p);
    segment.normals.push_back(n);
    segment.confidence.push_back(1.0f);
    segment.pixel.push_back(static_cast<int>(i));
  }
  segment.probability.assign(segment.size(), 1.0f / static_cast<float>(segment.size()));
  return segment;
}

class IcpRefinerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    model_ = prepareModel(asymmetricMesh(), ModelSamplingParams{});
    for (const Eigen::Vector3f& q : model_.points) centre_ += q;
    centre_ /= static_cast<float>(model_.size());
  }

  /// `truth` turned by `angle` radians about the model's centre.
  Eigen::Isometry3f turned(const Eigen::Isometry3f& truth, float angle) const {
    Eigen::Isometry3f pose = truth;
    pose.translate(centre_);
    pose.rotate(Eigen::AngleAxisf(angle, Eigen::Vector3f(1, -2, 1).normalized()));
    pose.translate(-centre_);
    return pose;
  }

  double addOf(const Eigen::Isometry3f& pose, const Eigen::Isometry3f& truth) const {
    return addError(model_.points,
                    {pose.linear().cast<double>(), pose.translation().cast<double>()},
                    {truth.linear().cast<double>(), truth.translation().cast<double>()});
  }

  ObjectModel model_;
  Eigen::Vector3f centre_ = Eigen::Vector3f::Zero();
};

// Steps are rotations about the model's centre: about the camera origin, a metre away, a step of
// w radians misplaces the model by about |w|^2 / 2 metres beyond the linear model, which made the
// first step from 0.08 rad off remove 3% of the error instead of 95%, and a start 0.2 rad off lose
// its correspondences and end 17 mm away.
TEST_F(IcpRefinerTest, StepsTurnTheModelAboutItsCentre) {
  const Eigen::Isometry3f truth = test::viewingPose(1.0f);
  const SoftSegment segment = visibleSamples(model_, truth);
  IcpParams params;
  params.iterations = 1;
  const Eigen::Isometry3f near_start = turned(truth, 0.08f);
  const double before = addOf(near_start, truth);
  EXPECT_GT(before, 0.002);
  EXPECT_LT(addOf(IcpRefiner(segment, params).refine(model_, near_start, -1), truth), 0.2 * before);

  params.iterations = 5;
  const Eigen::Isometry3f far_start = turned(truth, 0.2f);
  EXPECT_GT(addOf(far_start, truth), 0.005);
  EXPECT_LT(addOf(IcpRefiner(segment, params).refine(model_, far_start, -1), truth), 1e-4);
}

TEST_F(IcpRefinerTest, RunningOnInStepsTakesTheSameStepsAsOneRun) {
  const Eigen::Isometry3f truth = test::viewingPose(1.0f);
  const SoftSegment segment = visibleSamples(model_, truth);
  const IcpRefiner icp(segment, IcpParams{});
  const Eigen::Isometry3f start = turned(truth, 0.15f);
  IcpRun run(start);
  icp.iterate(model_, run, 2, -1);
  EXPECT_EQ(run.iterations, 2);
  EXPECT_FALSE(run.finished);
  icp.iterate(model_, run, 5, -1);
  icp.iterate(model_, run, 1000, -1);  // at most IcpParams::iterations in all
  EXPECT_LE(run.iterations, IcpParams{}.iterations);
  EXPECT_TRUE(run.finished || run.iterations == IcpParams{}.iterations);
  EXPECT_EQ(run.pose.matrix(), icp.refine(model_, start, -1).matrix());
  EXPECT_LT(addOf(run.pose, truth), 1e-4);
}

// With instance regions a refinement only takes correspondences in the pose's region, even where
// another region's points are closer.
TEST_F(IcpRefinerTest, CorrespondencesStayInTheRegion) {
  const Eigen::Isometry3f truth = test::viewingPose(1.0f);
  Eigen::Isometry3f behind = truth;
  behind.pretranslate(Eigen::Vector3f(0, 0, 0.008f));  // a second instance 8 mm further away
  SoftSegment segment = visibleSamples(model_, truth);
  const SoftSegment second = visibleSamples(model_, behind);
  segment.region.assign(segment.size(), 1);
  for (size_t i = 0; i < second.size(); ++i) {
    segment.points.push_back(second.points[i]);
    segment.normals.push_back(second.normals[i]);
    segment.confidence.push_back(1.0f);
    segment.pixel.push_back(second.pixel[i]);
    segment.region.push_back(2);
  }
  segment.probability.assign(segment.size(), 1.0f / static_cast<float>(segment.size()));
  Eigen::Isometry3f start = truth;
  start.pretranslate(Eigen::Vector3f(0, 0, 0.003f));  // nearer the first instance
  const IcpRefiner icp(segment, IcpParams{});
  EXPECT_LT(addOf(icp.refine(model_, start, 1), truth), 1e-4);
  EXPECT_LT(addOf(icp.refine(model_, start, 2), behind), 1e-4);
  EXPECT_LT(addOf(icp.refine(model_, start, -1), truth), 1e-4);  // all points: the nearer one
  EXPECT_TRUE(icp.refine(model_, start, 3).isApprox(start));     // a region without points
}

}  // namespace
}  // namespace stocs
