// Tracking (issue 30): a frame whose object moved a little is tracked from the predicted pose, an
// object whose map vanishes goes lost and is found again, a time jump ends the tracks, a follow
// slid along what ICP leaves loose comes back, and the constant-velocity prediction and the
// predicted box.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "stocs/eval/pose_metrics.h"
#include "stocs/io/ply_writer.h"
#include "stocs/sim/shape_meshes.h"
#include "stocs/stocs.h"
#include "stocs/tracking/segment_follower.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

constexpr double kFramePeriod = 1.0 / 30;

/// The pose moved by `mm` millimetres along a fixed direction and turned by `deg` degrees about a
/// fixed axis through the object's origin.
Eigen::Isometry3f moved(const Eigen::Isometry3f& pose, float mm, float deg) {
  Eigen::Isometry3f out = pose;
  out.translation() += Eigen::Vector3f(1, -0.5f, 0.3f).normalized() * (mm / 1000);
  out.linear() = Eigen::AngleAxisf(deg * static_cast<float>(M_PI) / 180,
                                   Eigen::Vector3f(0.2f, 1, 0.4f).normalized()) *
                 pose.linear();
  return out;
}

class TrackerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string file = (test::scratchDir("tracker") / "block.ply").string();
    writePly(file, asymmetricMesh(), 1000.0f);
    estimator_.addObject("block", file);
    model_ = estimator_.model("block");
    truth_ = test::viewingPose(0.6f);
  }

  /// Copies of the block rendered at the poses, the map `block` holding each one's value on it.
  static Frame blocksAt(const std::vector<std::pair<Eigen::Isometry3f, float>>& blocks) {
    const CameraIntrinsics camera = test::testCamera();
    std::vector<test::PlacedMesh> meshes;
    for (const auto& [pose, map] : blocks) meshes.push_back({asymmetricMesh(), pose});
    cv::Mat labels;
    const cv::Mat depth = test::renderDepth(meshes, camera, &labels);
    Frame frame = Frame::fromDepth(depth, camera, 1.0);
    cv::Mat probability(labels.size(), CV_32FC1, cv::Scalar(0));
    for (size_t k = 0; k < blocks.size(); ++k) {
      probability.setTo(blocks[k].second, labels == static_cast<int>(k + 1));
    }
    frame.probabilities["block"] = probability;
    return frame;
  }

  /// The block at `pose` (map 0.9) unless `gone`, before a wall 0.3 m behind it, and, when
  /// `occluded`, a board 0.1 m in front of it hiding it.
  static Frame sceneAt(const Eigen::Isometry3f& pose, bool occluded, bool gone = false) {
    const Eigen::Vector3f centre = pose * Eigen::Vector3f::Zero();
    std::vector<test::PlacedMesh> meshes;
    if (!gone) meshes.push_back({asymmetricMesh(), pose});
    const auto at = [](const Eigen::Vector3f& p) {
      return Eigen::Isometry3f(Eigen::Translation3f(p));
    };
    if (occluded) {
      meshes.push_back(
          {boxMesh({0.3f, 0.3f, 0.01f}), at(centre + Eigen::Vector3f(0.09f, 0, -0.1f))});
    }
    meshes.push_back({boxMesh({2, 2, 0.01f}), at(centre + Eigen::Vector3f(0, 0, 0.3f))});
    cv::Mat labels;
    const cv::Mat depth = test::renderDepth(meshes, test::testCamera(), &labels);
    Frame frame = Frame::fromDepth(depth, test::testCamera(), 1.0);
    cv::Mat probability(labels.size(), CV_32FC1, cv::Scalar(0));
    if (!gone) probability.setTo(0.9, labels == 1);
    frame.probabilities["block"] = probability;
    return frame;
  }

  /// The block rendered at `pose`, with a map of 0.9 on it (or none at all).
  static Frame frameAt(const Eigen::Isometry3f& pose, bool with_map = true) {
    return blocksAt({{pose, with_map ? 0.9f : 0.0f}});
  }

  FrameTracking track(FrameTracker& tracker, const Frame& frame, double stamp) const {
    return tracker.track(frame, {{"block", model_.get()}}, estimator_.params(), stamp);
  }

  double adds(const Eigen::Isometry3f& estimate, const Eigen::Isometry3f& truth) const {
    return addsError(model_->model.points,
                     {estimate.linear().cast<double>(), estimate.translation().cast<double>()},
                     {truth.linear().cast<double>(), truth.translation().cast<double>()});
  }

  Estimator estimator_{PipelineParams{}, ModelCache(test::scratchDir("tracker_cache"))};
  std::shared_ptr<const PreparedModel> model_;
  Eigen::Isometry3f truth_;
};

TEST_F(TrackerTest, APerturbedFrameIsTrackedFromThePrediction) {
  FrameTracker tracker{TrackingParams{}};
  const FrameTracking first = track(tracker, frameAt(truth_), 0.0);
  ASSERT_EQ(first.objects.size(), 1u);
  ASSERT_EQ(first.objects[0].states, std::vector<TrackState>{TrackState::kRedetected});
  EXPECT_TRUE(first.objects[0].detected);
  EXPECT_EQ(first.counts.redetected, 1);
  // A new track is confirmed by a second detection on the next frame.
  EXPECT_TRUE(track(tracker, frameAt(truth_), kFramePeriod).objects[0].detected);

  // The object moved 6 mm and turned 4 degrees by the next frame.
  const Eigen::Isometry3f next = moved(truth_, 6, 4);
  const FrameTracking second = track(tracker, frameAt(next), 2 * kFramePeriod);
  const TrackedObject& o = second.objects[0];
  ASSERT_EQ(o.states, std::vector<TrackState>{TrackState::kTracked});
  EXPECT_FALSE(o.detected);
  EXPECT_EQ(second.counts.tracked, 1);
  EXPECT_EQ(second.counts.detections, 0);
  const InstancePose& pose = o.result.estimate.instances.at(0);
  EXPECT_TRUE(pose.accepted) << pose.rejection;
  EXPECT_LT(adds(pose.pose, next), 0.02 * model_->model.diameter);
  EXPECT_EQ(pose.evidence.consensus, 0.0f);  // a followed pose has no bases
  EXPECT_GT(o.result.estimate.segment_points, 0u);
}

TEST_F(TrackerTest, AnObjectMovingSteadilyStaysTrackedAndAccurate) {
  FrameTracker tracker{TrackingParams{}};
  track(tracker, frameAt(truth_), 0.0);
  // 8 mm and 3 degrees a frame (24 cm/s, 90 deg/s at 30 Hz): the velocity carries the prediction.
  for (int k = 1; k <= 5; ++k) {
    const Eigen::Isometry3f at = moved(truth_, 8.0f * k, 3.0f * k);
    const FrameTracking t = track(tracker, frameAt(at), k * kFramePeriod);
    ASSERT_EQ(t.objects[0].states, std::vector<TrackState>{TrackState::kTracked}) << "frame " << k;
    EXPECT_LT(adds(t.objects[0].result.estimate.instances.at(0).pose, at),
              0.02 * model_->model.diameter)
        << "frame " << k;
  }
  const Track& track_now = tracker.objects().at("block").tracks().at(0);
  EXPECT_GT(track_now.motion.linear().norm(), 0.15f);  // m/s, measured from the poses
}

TEST_F(TrackerTest, InstancesKeepTheirIndicesWhileTheyMove) {
  PipelineParams params = estimator_.params();
  params.stocs.instances = 2;
  // Two copies of the block side by side.
  Eigen::Isometry3f left = truth_, right = truth_;
  left.translation().x() -= 0.08f;
  right.translation().x() += 0.08f;
  const auto frameOf = [](const Eigen::Isometry3f& a, const Eigen::Isometry3f& b) {
    return blocksAt({{a, 0.9f}, {b, 0.9f}});
  };
  FrameTracker tracker{TrackingParams{}};
  const FrameTracking first =
      tracker.track(frameOf(left, right), {{"block", model_.get()}}, params, 0.0);
  const std::vector<InstancePose>& found = first.objects.at(0).result.estimate.instances;
  ASSERT_EQ(found.size(), 2u);
  const bool left_first = adds(found[0].pose, left) < adds(found[1].pose, left);
  for (int k = 1; k <= 3; ++k) {
    const Eigen::Isometry3f a = moved(left, 5.0f * k, 2.0f * k), b = moved(right, -5.0f * k, 0);
    const FrameTracking t =
        tracker.track(frameOf(a, b), {{"block", model_.get()}}, params, k * kFramePeriod);
    const TrackedObject& o = t.objects.at(0);
    ASSERT_EQ(o.states, (std::vector<TrackState>{TrackState::kTracked, TrackState::kTracked}));
    const std::vector<InstancePose>& now = o.result.estimate.instances;
    const double limit = 0.05 * model_->model.diameter;
    EXPECT_LT(adds(now[left_first ? 0 : 1].pose, a), limit) << "frame " << k;
    EXPECT_LT(adds(now[left_first ? 1 : 0].pose, b), limit) << "frame " << k;
  }
}

TEST_F(TrackerTest, ScheduledDetectionMovesATrackOffALookAlike) {
  // The track holds a block the map marks faintly; the map marks another block strongly: the
  // tracked pose is accepted, but the scheduled detection finds the other block with a higher
  // confidence, and the track moves there.
  Eigen::Isometry3f faint = truth_, strong = truth_;
  faint.translation().x() -= 0.08f;
  strong.translation().x() += 0.08f;
  const Frame both = blocksAt({{faint, 0.9f}, {strong, 0.0f}});  // first only the faint one
  const Frame look_alike = blocksAt({{faint, 0.5f}, {strong, 0.95f}});

  TrackingParams params;
  params.redetect_every = 2;
  FrameTracker tracker(params);
  const auto poseAt = [&](const FrameTracking& t) {
    return t.objects.at(0).result.estimate.instances.at(0);
  };
  ASSERT_LT(adds(poseAt(track(tracker, both, 0.0)).pose, faint), 0.05 * model_->model.diameter);
  ASSERT_TRUE(track(tracker, both, kFramePeriod).objects[0].detected);  // the confirmation
  const FrameTracking held = track(tracker, look_alike, 2 * kFramePeriod);
  ASSERT_EQ(held.objects[0].states[0], TrackState::kTracked);  // accepted where it was
  EXPECT_LT(adds(poseAt(held).pose, faint), 0.05 * model_->model.diameter);
  const FrameTracking checked = track(tracker, look_alike, 3 * kFramePeriod);
  ASSERT_TRUE(checked.objects[0].detected);
  EXPECT_EQ(checked.objects[0].states[0], TrackState::kRedetected);
  EXPECT_LT(adds(poseAt(checked).pose, strong), 0.05 * model_->model.diameter);
  EXPECT_GT(poseAt(checked).confidence, poseAt(held).confidence);
}

TEST_F(TrackerTest, ScheduledDetectionTurnsATrackHeldAtTheRightPlaceTheWrongWay) {
  // Between two frames the block turns about its centre: following from the last pose may settle
  // turned the wrong way at the right place; the scheduled detection there, which the confidence
  // prefers, replaces it.
  const Eigen::Vector3f centre = truth_ * PoseProximity(model_->model).centre();
  Eigen::Isometry3f turned = truth_;
  turned.linear() =
      Eigen::AngleAxisf(0.5f * static_cast<float>(M_PI), truth_.linear().col(2)) * truth_.linear();
  turned.translation() = centre - turned.linear() * PoseProximity(model_->model).centre();
  TrackingParams params;
  params.redetect_every = 1;
  FrameTracker tracker(params);
  track(tracker, frameAt(truth_), 0.0);
  const FrameTracking t = track(tracker, frameAt(turned), kFramePeriod);
  const InstancePose& pose = t.objects.at(0).result.estimate.instances.at(0);
  ASSERT_TRUE(pose.accepted);
  EXPECT_LT(adds(pose.pose, turned), 0.05 * model_->model.diameter)
      << toString(t.objects[0].states[0]);
}

TEST_F(TrackerTest, AnObjectWhoseMapVanishesIsLostThenFoundAgain) {
  FrameTracker tracker{TrackingParams{}};
  track(tracker, frameAt(truth_), 0.0);
  const FrameTracking gone = track(tracker, frameAt(truth_, false), kFramePeriod);
  const TrackedObject& o = gone.objects[0];
  ASSERT_EQ(o.states, std::vector<TrackState>{TrackState::kLost});
  EXPECT_TRUE(o.detected);  // detection tried
  EXPECT_EQ(gone.counts.lost, 1);
  const InstancePose& pose = o.result.estimate.instances.at(0);
  EXPECT_FALSE(pose.accepted);
  EXPECT_EQ(pose.rejection.rfind("lost: ", 0), 0u) << pose.rejection;
  EXPECT_NE(pose.rejection.find("detection found no accepted pose for it"), std::string::npos)
      << pose.rejection;

  // Detection keeps trying, and the object comes back as the same instance.
  const FrameTracking back = track(tracker, frameAt(truth_), 2 * kFramePeriod);
  ASSERT_EQ(back.objects[0].states, std::vector<TrackState>{TrackState::kRedetected});
  EXPECT_TRUE(back.objects[0].result.estimate.instances.at(0).accepted);
  const FrameTracking tracked = track(tracker, frameAt(truth_), 3 * kFramePeriod);
  EXPECT_EQ(tracked.objects[0].states, std::vector<TrackState>{TrackState::kTracked});
}

TEST_F(TrackerTest, AnObjectHiddenBehindANearerSurfaceIsHeldThenTrackedAgain) {
  FrameTracker tracker{TrackingParams{}};
  track(tracker, sceneAt(truth_, false), 0.0);
  track(tracker, sceneAt(truth_, false), kFramePeriod);  // the new track confirmed
  const FrameTracking hidden = track(tracker, sceneAt(truth_, true), 2 * kFramePeriod);
  const TrackedObject& o = hidden.objects.at(0);
  ASSERT_EQ(o.states, std::vector<TrackState>{TrackState::kHidden});
  EXPECT_EQ(hidden.counts.hidden, 1);
  EXPECT_EQ(hidden.counts.lost, 0);
  const InstancePose& held = o.result.estimate.instances.at(0);
  EXPECT_FALSE(held.accepted);
  EXPECT_EQ(held.rejection.rfind("hidden behind a nearer surface, held: ", 0), 0u)
      << held.rejection;
  EXPECT_LT(adds(held.pose, truth_), 0.02 * model_->model.diameter);  // the last accepted pose

  const FrameTracking back = track(tracker, sceneAt(truth_, false), 3 * kFramePeriod);
  ASSERT_EQ(back.objects[0].states, std::vector<TrackState>{TrackState::kTracked});
  EXPECT_TRUE(back.objects[0].result.estimate.instances.at(0).accepted);
}

TEST_F(TrackerTest, AHiddenObjectIsLostWhenNotHeldOrWhenItLeftMeanwhile) {
  TrackingParams not_held;
  not_held.hold_hidden = false;
  FrameTracker plain(not_held);
  track(plain, sceneAt(truth_, false), 0.0);
  track(plain, sceneAt(truth_, false), kFramePeriod);
  const FrameTracking searched = track(plain, sceneAt(truth_, true), 2 * kFramePeriod);
  EXPECT_NE(searched.objects.at(0).states.at(0), TrackState::kHidden);
  EXPECT_EQ(searched.counts.hidden, 0);

  // Held while hidden; once the board is gone the wall shows through where it was: lost.
  FrameTracker tracker{TrackingParams{}};
  track(tracker, sceneAt(truth_, false), 0.0);
  track(tracker, sceneAt(truth_, false), kFramePeriod);
  ASSERT_EQ(track(tracker, sceneAt(truth_, true), 2 * kFramePeriod).objects.at(0).states,
            std::vector<TrackState>{TrackState::kHidden});
  EXPECT_EQ(track(tracker, sceneAt(truth_, false, true), 3 * kFramePeriod).objects.at(0).states,
            std::vector<TrackState>{TrackState::kLost});
}

TEST_F(TrackerTest, ALookAlikeOnAnotherObjectsSurfaceIsLostInEveryFrame) {
  // "twin" has the block's shape and a map that marks the block fainter than the block's own:
  // alone it would be tracked there; the frame-level explanation gives the surface to the block.
  const std::string file = (test::scratchDir("tracker") / "twin.ply").string();
  writePly(file, asymmetricMesh(), 1000.0f);
  estimator_.addObject("twin", file);
  const std::vector<FrameObject> objects = {{"block", model_.get()},
                                            {"twin", estimator_.model("twin").get()}};
  FrameTracker tracker{TrackingParams{}};
  for (int k = 0; k < 3; ++k) {
    Frame frame = frameAt(moved(truth_, 2.0f * k, 1.0f * k));
    frame.probabilities["twin"] = frame.probabilities["block"] * (0.6 / 0.9);
    const FrameTracking t = tracker.track(frame, objects, estimator_.params(), k * kFramePeriod);
    ASSERT_EQ(t.objects.size(), 2u);
    EXPECT_EQ(t.objects[0].states.at(0), k == 0 ? TrackState::kRedetected : TrackState::kTracked);
    EXPECT_TRUE(t.objects[0].result.estimate.instances.at(0).accepted);
    ASSERT_EQ(t.objects[1].states, std::vector<TrackState>{TrackState::kLost}) << k;
    EXPECT_EQ(t.objects[1].result.estimate.instances.at(0).rejection, "lost: explained by block 0");
    EXPECT_EQ(t.counts.lost, 1);
  }
}

TEST_F(TrackerTest, AGapOrTimeGoingBackEndsTheTracks) {
  FrameTracker tracker{TrackingParams{}};
  track(tracker, frameAt(truth_), 10.0);
  EXPECT_EQ(track(tracker, frameAt(truth_), 10.0 + kFramePeriod).objects[0].states[0],
            TrackState::kTracked);
  // Past max_gap (0.5 s): detected anew, not tracked.
  const FrameTracking late = track(tracker, frameAt(truth_), 11.0);
  EXPECT_TRUE(late.counts.reset);
  EXPECT_EQ(late.objects[0].states[0], TrackState::kRedetected);
  EXPECT_TRUE(late.objects[0].detected);
  // A bag played in a loop: the stamp goes back.
  const FrameTracking loop = track(tracker, frameAt(truth_), 1.0);
  EXPECT_TRUE(loop.counts.reset);
  EXPECT_EQ(loop.objects[0].states[0], TrackState::kRedetected);
  EXPECT_FALSE(track(tracker, frameAt(truth_), 1.0 + kFramePeriod).counts.reset);
}

TEST_F(TrackerTest, TheGapIsTheInputsNotTheTimeTheTrackerTook) {
  FrameTracker tracker{TrackingParams{}};
  const std::vector<FrameObject> objects = {{"block", model_.get()}};
  const Frame frame = frameAt(truth_);
  tracker.track(frame, objects, estimator_.params(), 0.0);
  // Input frames were skipped while the tracker worked: 2 s since the frame it tracked, but the
  // input's previous frame came a frame period before this one.
  const FrameTracking skipped =
      tracker.track(frame, objects, estimator_.params(), 2.0, 2.0 - kFramePeriod);
  EXPECT_FALSE(skipped.counts.reset);
  EXPECT_EQ(skipped.objects[0].states[0], TrackState::kTracked);
  // The input itself paused for a second.
  const FrameTracking paused = tracker.track(frame, objects, estimator_.params(), 3.0, 2.0);
  EXPECT_TRUE(paused.counts.reset);
  EXPECT_EQ(paused.objects[0].states[0], TrackState::kRedetected);
}

TEST_F(TrackerTest, DetectionRunsOnScheduleWhileTracked) {
  TrackingParams params;
  params.redetect_every = 2;
  FrameTracker tracker(params);
  std::vector<bool> detected;
  for (int k = 0; k < 5; ++k) {
    const FrameTracking t = track(tracker, frameAt(truth_), k * kFramePeriod);
    detected.push_back(t.objects[0].detected);
    EXPECT_EQ(t.objects[0].result.estimate.instances.size(), 1u);  // one track, index 0
  }
  // Frame 1 confirms the new track, then every second frame.
  EXPECT_EQ(detected, (std::vector<bool>{true, true, false, true, false}));
}

TEST_F(TrackerTest, OneScheduledDetectionAFrame) {
  TrackingParams params;
  params.redetect_every = 2;
  FrameTracker tracker(params);
  Frame frame = frameAt(truth_);
  frame.probabilities["copy"] = frame.probabilities["block"];  // a second object, the same block
  std::vector<bool> first, second;
  for (int k = 0; k < 5; ++k) {
    const FrameTracking t = tracker.track(frame, {{"block", model_.get()}, {"copy", model_.get()}},
                                          estimator_.params(), k * kFramePeriod);
    first.push_back(t.objects.at(0).detected);
    second.push_back(t.objects.at(1).detected);
  }
  // Both new tracks are to be confirmed on frame 1: the first object detects there, the second
  // one frame later; then each every second frame.
  EXPECT_EQ(first, (std::vector<bool>{true, true, false, true, false}));
  EXPECT_EQ(second, (std::vector<bool>{true, false, true, false, true}));
}

/// The poses of every object over three frames of a moving block, `threads` following at once.
std::vector<Eigen::Matrix4f> posesOverFrames(FrameTracker& tracker,
                                             const std::vector<FrameObject>& objects,
                                             PipelineParams params, const Frame (&frames)[3],
                                             int threads) {
  params.stocs.threads = threads;
  std::vector<Eigen::Matrix4f> poses;
  for (int k = 0; k < 3; ++k) {
    for (const TrackedObject& o :
         tracker.track(frames[k], objects, params, k * kFramePeriod).objects) {
      poses.push_back(o.result.estimate.instances.at(0).pose.matrix());
    }
  }
  return poses;
}

TEST_F(TrackerTest, ObjectsFollowedInParallelMatchThoseFollowedInTurn) {
  Frame frames[3] = {frameAt(truth_), frameAt(moved(truth_, 4, 1)), frameAt(moved(truth_, 8, 2))};
  std::vector<FrameObject> objects;  // four objects of the same block: their poses must agree
  for (const char* name : {"block", "b", "c", "d"}) objects.push_back({name, model_.get()});
  for (Frame& f : frames) {
    for (const FrameObject& o : objects) f.probabilities[o.name] = f.probabilities.at("block");
  }
  // Four objects on one surface: the frame-level explanation would keep one and leave the others
  // to detection; here all four are followed.
  PipelineParams params = estimator_.params();
  params.explanation.enabled = false;
  FrameTracker in_turn{TrackingParams{}}, in_parallel{TrackingParams{}};
  const auto expected = posesOverFrames(in_turn, objects, params, frames, 1);
  const auto actual = posesOverFrames(in_parallel, objects, params, frames, 2);
  ASSERT_EQ(actual.size(), expected.size());
  for (size_t k = 0; k < expected.size(); ++k)
    EXPECT_TRUE(actual[k].isApprox(expected[k], 1e-6f)) << k;
}

/// A detection of one accepted pose with `evidence` (and its confidence) whose bases all found
/// `bases_at`, for merging.
PoseEstimate detectionOf(const Eigen::Isometry3f& pose, ConfidenceEvidence evidence,
                         const Eigen::Isometry3f& bases_at, const ConfidenceParams& params) {
  PoseEstimate e;
  e.base_poses.assign(ConfidenceEvidence::kConsensusBases, bases_at);
  InstancePose p;
  p.pose = pose;
  evidence.consensus = 1;
  p.evidence = evidence;
  p.confidence = params.confidence(evidence);
  p.accepted = true;
  e.instances.push_back(p);
  return e;
}

TEST_F(TrackerTest, AMergedDetectionReplacesATrackedPoseOnlyWhenPreferred) {
  ObjectTracker tracker{TrackingParams{}};
  const Frame frame = frameAt(truth_);
  const CameraIntrinsics camera = frameCamera(frame);  // the input points to it
  const PipelineParams& params = estimator_.params();
  const ObjectInput in = objectInput(frame, camera, {"block", model_.get()}, params);
  tracker.update(in, 0.0);
  tracker.update(in, kFramePeriod);
  ASSERT_EQ(tracker.tracks().at(0).state, TrackState::kTracked);
  const ConfidenceEvidence held = tracker.tracks()[0].pose.evidence;
  ASSERT_EQ(held.consensus, 0.0f);  // a followed pose has no bases of its own
  const Eigen::Isometry3f before = tracker.tracks()[0].pose.pose;
  const Eigen::Isometry3f near = moved(truth_, 3, 0);  // the track's place
  Eigen::Isometry3f far = truth_;
  far.translation().x() += model_->model.diameter;  // beyond the match distance
  ConfidenceEvidence worse = held;                  // less of the model matched
  worse.matched *= 0.9f;
  // At the track's place, with bases that agree with the tracked pose as well: its confidence is
  // higher than the tracked pose's only through the consensus, which the tracked pose shares.
  const PoseEstimate same_place = detectionOf(near, worse, near, params.confidence);
  ASSERT_GT(same_place.instances[0].confidence, tracker.tracks()[0].pose.confidence);
  EXPECT_TRUE(tracker.merge(same_place, *model_, params).empty());
  // Elsewhere, with bases that found the tracked pose: not preferred either.
  EXPECT_TRUE(
      tracker.merge(detectionOf(far, worse, truth_, params.confidence), *model_, params).empty());
  EXPECT_TRUE(tracker.tracks()[0].pose.pose.isApprox(before));
  EXPECT_EQ(tracker.tracks()[0].state, TrackState::kTracked);
  // Elsewhere, as good on the evidence and backed by every base: it replaces the pose, as a
  // detection of the track (its index stays, no motion).
  EXPECT_EQ(tracker.merge(detectionOf(far, held, far, params.confidence), *model_, params),
            std::vector<int>{0});
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_TRUE(tracker.tracks()[0].pose.pose.isApprox(far));
  EXPECT_EQ(tracker.tracks()[0].state, TrackState::kRedetected);
  EXPECT_EQ(tracker.tracks()[0].motion.linear().norm(), 0.0f);
  // Room for a second instance: a pose elsewhere starts a new track and the first one stays.
  PipelineParams two = params;
  two.stocs.instances = 2;
  EXPECT_EQ(tracker.merge(detectionOf(truth_, worse, truth_, params.confidence), *model_, two),
            std::vector<int>{1});
  ASSERT_EQ(tracker.tracks().size(), 2u);
  EXPECT_EQ(tracker.tracks()[1].index, 1);
  EXPECT_TRUE(tracker.tracks()[0].pose.pose.isApprox(far));
}

TEST_F(TrackerTest, ADetectionThatFitsTheTracksTurnAsWellKeepsIt) {
  // The detection, which the confidence prefers, is the tracked block turned by a half about its
  // long axis and names the tracked turn as fitting as well (a box whose print is out of view):
  // the track keeps its turn and names the detection's. One that names no such turn replaces it.
  const Frame frame = frameAt(truth_);
  const CameraIntrinsics camera = frameCamera(frame);  // the input points to it
  const PipelineParams& params = estimator_.params();
  const ObjectInput in = objectInput(frame, camera, {"block", model_.get()}, params);
  const Eigen::Vector3f centre = PoseProximity(model_->model).centre();
  Eigen::Isometry3f half_turn = Eigen::Isometry3f::Identity();  // model frame, about the centre
  half_turn.linear() =
      Eigen::AngleAxisf(static_cast<float>(M_PI), Eigen::Vector3f::UnitX()).toRotationMatrix();
  half_turn.translation() = centre - half_turn.linear() * centre;
  // The track's pose after a detection at its turn, naming `ambiguous`.
  const auto merged = [&](const std::vector<ShapeAlternative>& ambiguous,
                          Eigen::Isometry3f& turned) {
    ObjectTracker tracker{TrackingParams{}};
    tracker.update(in, 0.0);
    tracker.update(in, kFramePeriod);
    EXPECT_EQ(tracker.tracks().at(0).state, TrackState::kTracked);
    turned = tracker.tracks()[0].pose.pose * half_turn;
    ConfidenceEvidence better = tracker.tracks()[0].pose.evidence;
    better.surface_confirmed = better.matched = better.map_support = 1;
    better.free_space = 0;
    PoseEstimate detection = detectionOf(turned, better, turned, params.confidence);
    detection.instances[0].ambiguous = ambiguous;
    EXPECT_EQ(tracker.merge(detection, *model_, params), std::vector<int>{0});
    return tracker.tracks()[0].pose;
  };
  Eigen::Isometry3f turned;
  const InstancePose kept = merged({shapeAlternative(half_turn.inverse(), 0.001f)}, turned);
  EXPECT_TRUE((kept.pose * half_turn).isApprox(turned, 1e-4f)) << "the track took the turn";
  ASSERT_EQ(kept.ambiguous.size(), 1u);
  EXPECT_TRUE((kept.pose * kept.ambiguous[0].motion).isApprox(turned, 1e-4f));
  EXPECT_NEAR(kept.ambiguous[0].angle, static_cast<float>(M_PI), 1e-3f);
  EXPECT_EQ(kept.ambiguous[0].shift, 0.001f);

  const InstancePose replaced = merged({}, turned);
  EXPECT_TRUE(replaced.pose.isApprox(turned));
  EXPECT_TRUE(replaced.ambiguous.empty());
}

TEST_F(TrackerTest, AHiddenTrackIsHeldAgainstADetectionThatTurnsIt) {
  ObjectTracker tracker{TrackingParams{}};
  const PipelineParams& params = estimator_.params();
  const Frame visible = sceneAt(truth_, false), hidden = sceneAt(truth_, true);
  const CameraIntrinsics camera = frameCamera(visible);  // the inputs point to it
  const ObjectInput seen = objectInput(visible, camera, {"block", model_.get()}, params);
  const ObjectInput behind = objectInput(hidden, camera, {"block", model_.get()}, params);
  tracker.update(seen, 0.0);
  tracker.update(seen, kFramePeriod);
  ConfidenceEvidence worse = tracker.tracks().at(0).pose.evidence;  // less of the model matched
  worse.matched *= 0.9f;
  tracker.followOnly(behind, kFramePeriod);
  ASSERT_EQ(tracker.tracks().at(0).state, TrackState::kHidden);
  // Turned a quarter about the camera's axis at the same place (as the visible part of a partly
  // hidden object may fit), with bases that agree with the held pose as well: not preferred.
  const Eigen::Vector3f centre = truth_ * PoseProximity(model_->model).centre();
  Eigen::Isometry3f turned = truth_;
  turned.linear() = Eigen::AngleAxisf(0.5f * static_cast<float>(M_PI), Eigen::Vector3f::UnitZ()) *
                    truth_.linear();
  turned.translation() = centre - turned.linear() * PoseProximity(model_->model).centre();
  EXPECT_TRUE(tracker.merge(detectionOf(turned, worse, truth_, params.confidence), *model_, params)
                  .empty());
  EXPECT_EQ(tracker.tracks().at(0).state, TrackState::kHidden);
  ASSERT_EQ(tracker.tracks().size(), 1u);
  // The held pose found again, with as little evidence: taken.
  const Eigen::Isometry3f near = moved(truth_, 3, 1);
  EXPECT_EQ(tracker.merge(detectionOf(near, worse, truth_, params.confidence), *model_, params),
            std::vector<int>{0});
  EXPECT_EQ(tracker.tracks()[0].state, TrackState::kRedetected);
  EXPECT_TRUE(tracker.tracks()[0].pose.pose.isApprox(near));
}

TEST_F(TrackerTest, FollowingOnlyLosesAFailedTrackAndAMergedDetectionFindsItAgain) {
  FrameTracker tracker{TrackingParams{}};
  const std::vector<FrameObject> objects = {{"block", model_.get()}};
  const PipelineParams& params = estimator_.params();
  const Frame frame = frameAt(truth_);
  // No track yet: nothing published, detection wanted.
  const FrameTracking none = tracker.follow(frame, objects, params, 0.0, std::nullopt, nullptr);
  EXPECT_TRUE(none.objects.at(0).result.estimate.instances.empty());
  EXPECT_FALSE(none.objects[0].detected);
  ASSERT_EQ(tracker.detectionWanted(objects).size(), 1u);
  // The detection of that frame, merged at the next one: followed from there, redetected.
  const FrameDetection detection{tracker.generation(), estimateFrame(frame, objects, params)};
  const Eigen::Isometry3f next = moved(truth_, 4, 2);
  const FrameTracking found =
      tracker.follow(frameAt(next), objects, params, kFramePeriod, std::nullopt, &detection);
  ASSERT_EQ(found.objects.at(0).states, std::vector<TrackState>{TrackState::kRedetected});
  EXPECT_TRUE(found.objects[0].detected);
  EXPECT_EQ(found.counts.detections, 1);
  EXPECT_LT(adds(found.objects[0].result.estimate.instances.at(0).pose, next),
            0.02 * model_->model.diameter);
  // The new track's confirmation is wanted; once merged, tracked with the schedule not due.
  ASSERT_EQ(tracker.detectionWanted(objects).size(), 1u);
  const FrameDetection confirmation{tracker.generation(),
                                    estimateFrame(frameAt(next), objects, params)};
  tracker.follow(frameAt(next), objects, params, 2 * kFramePeriod, std::nullopt, &confirmation);
  EXPECT_TRUE(tracker.detectionWanted(objects).empty());
  const FrameTracking tracked =
      tracker.follow(frameAt(next), objects, params, 3 * kFramePeriod, std::nullopt, nullptr);
  EXPECT_EQ(tracked.objects[0].states, std::vector<TrackState>{TrackState::kTracked});
  // The map vanishes: lost at once (no detection in the frame), and detection is wanted.
  const FrameTracking gone = tracker.follow(frameAt(next, false), objects, params, 4 * kFramePeriod,
                                            std::nullopt, nullptr);
  EXPECT_EQ(gone.objects[0].states, std::vector<TrackState>{TrackState::kLost});
  EXPECT_FALSE(gone.objects[0].detected);
  const InstancePose& lost = gone.objects[0].result.estimate.instances.at(0);
  EXPECT_FALSE(lost.accepted);
  // Detection did not run in this frame: the reason says it is still to come, not that it failed.
  EXPECT_NE(lost.rejection.find("; detection in the background has not found it again yet"),
            std::string::npos)
      << lost.rejection;
  EXPECT_EQ(tracker.detectionWanted(objects).size(), 1u);
}

TEST_F(TrackerTest, ADetectionOfEndedTracksIsNotMerged) {
  FrameTracker tracker{TrackingParams{}};
  const std::vector<FrameObject> objects = {{"block", model_.get()}};
  const PipelineParams& params = estimator_.params();
  const Frame frame = frameAt(truth_);
  tracker.follow(frame, objects, params, 5.0, std::nullopt, nullptr);
  const FrameDetection detection{tracker.generation(), estimateFrame(frame, objects, params)};
  // The bag looped while it ran: the tracks ended, and the detection is of another time.
  const FrameTracking loop = tracker.follow(frame, objects, params, 1.0, std::nullopt, &detection);
  EXPECT_TRUE(loop.counts.reset);
  EXPECT_FALSE(loop.objects.at(0).detected);
  EXPECT_TRUE(loop.objects[0].result.estimate.instances.empty());
}

TEST_F(TrackerTest, OneScheduledDetectionIsWantedAtATime) {
  TrackingParams params;
  params.redetect_every = 2;
  FrameTracker tracker(params);
  // Two blocks side by side, "copy" on the second: one surface would go to one of them (the
  // frame-level explanation).
  Eigen::Isometry3f beside = truth_;
  beside.translation().x() += 0.1f;
  Frame frame = blocksAt({{truth_, 0.9f}, {beside, 0.0f}});
  frame.probabilities["copy"] = blocksAt({{truth_, 0.0f}, {beside, 0.9f}}).probabilities["block"];
  frame.probabilities["new"] = frame.probabilities["copy"];
  const std::vector<FrameObject> both = {{"block", model_.get()}, {"copy", model_.get()}};
  tracker.track(frame, both, estimator_.params(), 0.0);  // both new tracks to be confirmed now
  std::vector<FrameObject> objects = both;
  objects.push_back({"new", model_.get()});  // no track: always wanted
  std::vector<std::string> wanted;
  for (const FrameObject& o : tracker.detectionWanted(objects)) wanted.push_back(o.name);
  EXPECT_EQ(wanted, (std::vector<std::string>{"block", "new"}));
}

TEST_F(TrackerTest, AStreamDetectsItsFirstFrameInPlace) {
  StreamTracker tracker{TrackingParams{}};
  const FrameTracking first = tracker.track(std::make_shared<const Frame>(frameAt(truth_)),
                                            {{"block", model_.get()}}, estimator_.params(), 0.0);
  EXPECT_FALSE(first.counts.reset);
  ASSERT_EQ(first.objects.at(0).states, std::vector<TrackState>{TrackState::kRedetected});
  EXPECT_TRUE(first.objects[0].detected);
  EXPECT_LT(adds(first.objects[0].result.estimate.instances.at(0).pose, truth_),
            0.02 * model_->model.diameter);
}

TEST_F(TrackerTest, AStreamDetectsInTheBackgroundAndMergesAtTheNextFrame) {
  StreamTracker tracker{TrackingParams{}};
  const std::vector<FrameObject> objects = {{"block", model_.get()}};
  const auto frame = [&](const Eigen::Isometry3f& at, bool with_map = true) {
    return std::make_shared<const Frame>(frameAt(at, with_map));
  };
  // The first frame, detected in place, has no block; the second starts a background detection.
  tracker.track(frame(truth_, false), objects, estimator_.params(), 0.0);
  const FrameTracking started =
      tracker.track(frame(truth_), objects, estimator_.params(), kFramePeriod);
  EXPECT_FALSE(started.objects.at(0).detected);
  tracker.waitForDetection();
  const Eigen::Isometry3f next = moved(truth_, 4, 2);
  const FrameTracking second =
      tracker.track(frame(next), objects, estimator_.params(), 2 * kFramePeriod);
  ASSERT_EQ(second.objects.at(0).states, std::vector<TrackState>{TrackState::kRedetected});
  EXPECT_LT(adds(second.objects[0].result.estimate.instances.at(0).pose, next),
            0.02 * model_->model.diameter);
  // That frame started the detection confirming the new track; merged at the next frame.
  tracker.waitForDetection();
  tracker.track(frame(next), objects, estimator_.params(), 3 * kFramePeriod);
  const FrameTracking fourth =
      tracker.track(frame(next), objects, estimator_.params(), 4 * kFramePeriod);
  EXPECT_EQ(fourth.objects[0].states, std::vector<TrackState>{TrackState::kTracked});
  EXPECT_FALSE(tracker.takeDetectionError());
}

// An object without a track has its last detection's best pose, rejected, in every frame of a
// stream: in the frame detected in place and in the followed frames after it.
TEST_F(TrackerTest, AnUntrackedObjectReportsItsLastDetectionsRejectionInEveryFrame) {
  PipelineParams params = estimator_.params();
  params.confidence.min_confidence = 0.999f;  // the detection's pose is found and rejected
  StreamTracker tracker{TrackingParams{}};
  const auto frame = std::make_shared<const Frame>(frameAt(truth_));
  for (int k = 0; k < 3; ++k) {
    const FrameTracking t =
        tracker.track(frame, {{"block", model_.get()}}, params, k * kFramePeriod);
    ASSERT_EQ(t.objects.at(0).states, std::vector<TrackState>{TrackState::kUntracked}) << k;
    const InstancePose& pose = t.objects[0].result.estimate.instances.at(0);
    EXPECT_FALSE(pose.accepted);
    EXPECT_GT(pose.confidence, 0.0f);
    EXPECT_LT(pose.confidence, params.confidence.min_confidence);
    EXPECT_EQ(pose.rejection.rfind("not tracked: the last detection's best pose: confidence", 0),
              0u)
        << pose.rejection;
    EXPECT_EQ(t.counts.lost, 0);
  }
  tracker.waitForDetection();
}

TEST_F(TrackerTest, AStreamSlowerThanTheGapIsDetectedInEachFrame) {
  StreamTracker tracker{TrackingParams{}};  // max_gap 0.5 s
  const std::vector<FrameObject> objects = {{"block", model_.get()}};
  const auto frame = std::make_shared<const Frame>(frameAt(truth_));
  tracker.track(frame, objects, estimator_.params(), 0.0);
  // Each frame a second later ends the tracks: detected in place, not left to a background
  // detection that the next frame would end again.
  for (int k = 1; k <= 2; ++k) {
    const FrameTracking t = tracker.track(frame, objects, estimator_.params(), k * 1.0);
    EXPECT_TRUE(t.counts.reset);
    ASSERT_EQ(t.objects.at(0).states, std::vector<TrackState>{TrackState::kRedetected}) << k;
    EXPECT_LT(adds(t.objects[0].result.estimate.instances.at(0).pose, truth_),
              0.02 * model_->model.diameter);
  }
}

// Frames keep coming while a background detection runs (the node's case): following the track and
// detecting read the same model at the same time (checked under ThreadSanitizer), and the object
// stays tracked at its place.
TEST_F(TrackerTest, AStreamFollowsFramesWhileItDetects) {
  TrackingParams params;
  params.redetect_every = 2;  // a detection starts at nearly every frame
  StreamTracker tracker{params};
  const std::vector<FrameObject> objects = {{"block", model_.get()}};
  Eigen::Isometry3f pose = truth_;
  double stamp = 0;
  FrameTracking last;
  for (int k = 0; k < 8; ++k, stamp += kFramePeriod) {
    pose = moved(pose, 1, 0.5f);
    last = tracker.track(std::make_shared<const Frame>(frameAt(pose)), objects, estimator_.params(),
                         stamp);
  }
  ASSERT_EQ(last.objects.at(0).result.estimate.instances.size(), 1u);
  EXPECT_LT(adds(last.objects[0].result.estimate.instances[0].pose, pose),
            0.02 * model_->model.diameter);
  tracker.waitForDetection();
  EXPECT_FALSE(tracker.takeDetectionError());
}

// Destroyed while its detection runs (the node's reload or shutdown), the stream tracker waits for
// it and releases its frame and what the caller asked to keep (the models' owner); run under the
// sanitizers (scripts/run_tests.sh), and under ThreadSanitizer when checking the thread's safety.
TEST_F(TrackerTest, AStreamTrackerDestroyedWhileItDetectsReleasesItsFrame) {
  auto frame = std::make_shared<const Frame>(frameAt(truth_));
  auto keep = std::make_shared<int>(0);
  const std::weak_ptr<const Frame> frame_held = frame;
  const std::weak_ptr<int> keep_held = keep;
  {
    StreamTracker tracker{TrackingParams{}};
    const std::vector<FrameObject> objects = {{"block", model_.get()}};
    // The first frame (no block) is detected in place; the second starts a background detection.
    tracker.track(std::make_shared<const Frame>(frameAt(truth_, false)), objects,
                  estimator_.params(), 0.0);
    tracker.track(std::move(frame), objects, estimator_.params(), kFramePeriod, std::nullopt,
                  std::move(keep));
  }
  EXPECT_TRUE(frame_held.expired());
  EXPECT_TRUE(keep_held.expired());
}

TEST_F(TrackerTest, AnObjectWithoutAMapIsNamed) {
  FrameTracker tracker{TrackingParams{}};
  const Frame frame = frameAt(truth_);
  try {
    tracker.track(frame, {{"block", model_.get()}, {"cup", model_.get()}}, estimator_.params(), 0);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("object 'cup'"), std::string::npos) << e.what();
  }
}

TEST_F(TrackerTest, BadParametersAreNamed) {
  TrackingParams params;
  params.max_gap = 0;
  try {
    FrameTracker{params};
    ADD_FAILURE() << "max_gap 0 was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("max_gap"), std::string::npos) << e.what();
  }
}

TEST(ConstantVelocity, PredictsAConstantMotionAndDampsIt) {
  const Eigen::Vector3f centre(0.01f, 0.02f, 0.03f);
  ConstantVelocity motion(centre);
  const Eigen::Isometry3f a = test::viewingPose(0.6f);
  const Eigen::Isometry3f b = moved(a, 5, 3);
  motion.update(a, b, 0.1);
  // Applying the same motion again from b: the centre moves as far again, the rotation repeats.
  const Eigen::Isometry3f c = motion.predict(b, 0.1, 1.0f);
  EXPECT_NEAR(((c * centre) - (b * centre) - ((b * centre) - (a * centre))).norm(), 0, 1e-6);
  const Eigen::Matrix3f turn = b.linear() * a.linear().transpose();
  EXPECT_TRUE((c.linear()).isApprox(turn * b.linear(), 1e-5f));
  EXPECT_TRUE(motion.predict(b, 0.1, 0.0f).isApprox(b));
  const Eigen::Isometry3f half = motion.predict(b, 0.1, 0.5f);
  EXPECT_NEAR(((half * centre) - (b * centre)).norm(), ((b * centre) - (a * centre)).norm() / 2,
              1e-6);
  motion.stop();
  EXPECT_TRUE(motion.predict(b, 0.1, 1.0f).isApprox(b));
}

// A long box lying on a board, seen on its top and its front: its ends face away, so sliding it
// along its length barely changes ICP's cost, but its end then hangs over board the sensor sees.
TEST(SegmentFollower, AFollowSlidAlongWhatICPLeavesLooseComesBack) {
  const MeshData box = boxMesh({0.18f, 0.045f, 0.05f});
  const std::string file = (test::scratchDir("slide") / "long_box.ply").string();
  writePly(file, box, 1000.0f);
  Estimator estimator{PipelineParams{}, ModelCache(test::scratchDir("slide_cache"))};
  estimator.addObject("long", file);
  const std::shared_ptr<const PreparedModel> model = estimator.model("long");
  // Its length across the view, its front and top turned 45 degrees towards the camera.
  const float s = std::sqrt(0.5f);
  Eigen::Isometry3f truth = Eigen::Isometry3f::Identity();
  truth.linear() << 1, 0, 0, 0, s, s, 0, -s, s;
  truth.translation() = Eigen::Vector3f(0, 0, 0.6f);
  const Eigen::Isometry3f board =
      truth * Eigen::Translation3f(0, 0, 0.03f);  // under the box's bottom face (+z)
  const CameraIntrinsics camera = test::testCamera();
  cv::Mat labels;
  const cv::Mat depth =
      test::renderDepth({{box, truth}, {boxMesh({0.6f, 0.6f, 0.01f}), board}}, camera, &labels);
  Frame frame = Frame::fromDepth(depth, camera, 1.0);
  cv::Mat probability(labels.size(), CV_32FC1, cv::Scalar(0));
  probability.setTo(0.9, labels == 1);
  frame.probabilities["long"] = probability;
  const ObjectInput in = objectInput(frame, camera, {"long", model.get()}, estimator.params());
  const SegmentFollower follower(in, cv::Rect(0, 0, camera.width, camera.height));
  // Predicted 10 mm along its length (5% of its diameter).
  const Eigen::Isometry3f predicted = truth * Eigen::Translation3f(0.01f, 0, 0);
  const InstancePose pose = follower.follow(predicted);
  EXPECT_LT((pose.pose.translation() - truth.translation()).norm(), 0.02 * model->model.diameter);
  EXPECT_TRUE(pose.accepted) << pose.rejection;
}

TEST(PredictedBox, HoldsTheObjectsImageAndStaysInTheImage) {
  const CameraIntrinsics camera = test::testCamera();
  const Eigen::Isometry3f pose = test::viewingPose(0.6f);
  cv::Mat labels;
  test::renderDepth({{asymmetricMesh(), pose}}, camera, &labels);
  ObjectModel model;
  model.points = asymmetricMesh().vertices;
  const PoseProximity extent(model);
  const cv::Rect box = predictedBox(extent, pose, camera, 0.0f);
  EXPECT_EQ(cv::countNonZero(labels(box) == 1), cv::countNonZero(labels == 1));
  EXPECT_LT(box.area(), camera.width * camera.height / 2);
  const cv::Rect wide = predictedBox(extent, pose, camera, 0.5f);
  EXPECT_GT(wide.area(), box.area());
  Eigen::Isometry3f behind = pose;
  behind.translation().z() = 0;
  EXPECT_EQ(predictedBox(extent, behind, camera, 0.5f),
            cv::Rect(0, 0, camera.width, camera.height));
}

}  // namespace
}  // namespace stocs
