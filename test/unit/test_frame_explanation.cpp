// The frame-level explanation on rendered boxes with hand-set poses, maps and confidences: an
// absent look-alike fitted on the present box, a second pose of one box in a bin, a worse-fitting
// object over a box where the maps mark both alike, two separate objects (nothing lost), and a
// pose on surface another object's map holds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "stocs/estimation/pose_estimate.h"
#include "stocs/estimation/stages/frame_explanation.h"
#include "test_support.h"

namespace stocs {
namespace {

const Eigen::Vector3f kBox(0.09f, 0.055f, 0.035f);
const Eigen::Vector3f kSmallBox(0.08f, 0.05f, 0.04f);  // within 20% per side: a look-alike

/// A box 0.6 m in front of the camera, its largest face towards it.
Eigen::Isometry3f at(float x, float y) {
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.translation() = Eigen::Vector3f(x, y, 0.6f);
  return pose;
}

InstancePose instance(const Eigen::Isometry3f& pose, float confidence) {
  InstancePose p;
  p.pose = pose;
  p.confidence = confidence;
  return p;
}

/// A depth frame of boxes of size kBox at `placed`, and a map per box of `level` on its pixels.
class FrameExplanationTest : public ::testing::Test {
 protected:
  void render(const std::vector<Eigen::Isometry3f>& placed) {
    std::vector<test::PlacedMesh> meshes;
    for (const Eigen::Isometry3f& pose : placed) meshes.push_back({boxMesh(kBox), pose});
    depth_ = test::renderDepth(meshes, camera_, &labels_);
    cloud_ = cloudFromDepth(depth_, camera_, 1.0);
  }
  /// `level` on the pixels of rendered box `index` (0-based), 0 elsewhere.
  cv::Mat map(int index, float level) const {
    cv::Mat m(labels_.size(), CV_32FC1, cv::Scalar(0));
    m.setTo(level, labels_ == index + 1);
    return m;
  }
  /// explainPoses with the maps of the poses' objects.
  std::vector<ExplainedPose> explain(std::vector<FramePose>& poses,
                                     const FrameExplanationParams& params = {},
                                     bool maps_name_objects = true) const {
    std::vector<ObjectMap> maps;
    for (const FramePose& p : poses) {
      const bool listed = std::any_of(maps.begin(), maps.end(),
                                      [&](const ObjectMap& m) { return m.object == p.object; });
      if (!listed) maps.push_back({p.object, p.probability});
    }
    return explainPoses(poses, FreeSpaceCheck(cloud_, camera_, FreeSpaceParams{}), params,
                        maps_name_objects, maps);
  }

  const CameraIntrinsics camera_ = test::testCamera();
  const ObjectModel box_ = prepareModel(boxMesh(kBox), ModelSamplingParams{});
  const ObjectModel small_box_ = prepareModel(boxMesh(kSmallBox), ModelSamplingParams{});
  cv::Mat depth_, labels_;
  OrganizedCloud cloud_;
};

TEST_F(FrameExplanationTest, AnAbsentLookAlikeOnThePresentBoxIsExplainedByIt) {
  const Eigen::Isometry3f pose = test::viewingPose(0.6f);
  render({pose});
  const cv::Mat box_map = map(0, 0.9f), small_map = map(0, 0.7f);  // both mark the box
  // The look-alike's confidence is the higher, its map x confidence too (0.665 against 0.63): the
  // maps say which object is there.
  InstancePose box = instance(pose, 0.70f), small = instance(pose, 0.95f);
  std::vector<FramePose> poses = {{"box", 0, &box_, &box_map, &box},
                                  {"small_box", 0, &small_box_, &small_map, &small}};
  const std::vector<ExplainedPose> explained = explain(poses);
  ASSERT_EQ(explained.size(), 1u);
  EXPECT_EQ(explained[0].pose, 1u);
  EXPECT_EQ(explained[0].by, 0u);
  // The surface the box explains is where the map marks it.
  const cv::Mat area = confirmedArea(poses, {true, false}, FreeSpaceCheck(cloud_, camera_, {}));
  EXPECT_GT(cv::countNonZero(area & (labels_ == 1)), 0.8 * cv::countNonZero(labels_ == 1));
  // Beyond the box only by a splat's half side (the sample spacing) at most.
  const int h = static_cast<int>(std::ceil(camera_.fx * box_.sampling_radius / 0.55));
  cv::Rect grown = cv::boundingRect(labels_ == 1);
  grown = cv::Rect(grown.x - h, grown.y - h, grown.width + 2 * h, grown.height + 2 * h);
  EXPECT_EQ(cv::boundingRect(area) & grown, cv::boundingRect(area));
  EXPECT_TRUE(box.accepted);
  EXPECT_FALSE(small.accepted);
  EXPECT_EQ(small.rejection, "explained by box 0");
  // The confidence's evidence: the share explained at the rejection; none left for the box.
  EXPECT_GT(small.evidence.explained, 0.5f);
  EXPECT_EQ(box.evidence.explained, 0.0f);
}

TEST_F(FrameExplanationTest, TwoPosesOfOneBoxInABinKeepOne) {
  const Eigen::Isometry3f a = at(-0.046f, 0), b = at(0.046f, 0);  // touching
  render({a, b});
  Eigen::Isometry3f slid = a;
  slid.translation().x() += 0.01f;  // the first box again, slid by a centimetre
  cv::Mat bin = map(0, 0.9f) + map(1, 0.9f);
  InstancePose first = instance(a, 0.92f), second = instance(slid, 0.90f),
               other = instance(b, 0.91f);
  std::vector<FramePose> poses = {{"box", 0, &box_, &bin, &first},
                                  {"box", 1, &box_, &bin, &second},
                                  {"box", 2, &box_, &bin, &other}};
  explain(poses);
  EXPECT_TRUE(first.accepted);
  EXPECT_TRUE(other.accepted);  // its neighbour shares only its outline
  EXPECT_FALSE(second.accepted);
  EXPECT_EQ(second.rejection, "explained by box 0");
  // Touching neighbours each explain a little of the other: their outlines.
  EXPECT_GT(first.evidence.explained, 0.0f);
  EXPECT_LT(first.evidence.explained, 0.25f);
  EXPECT_LT(other.evidence.explained, 0.25f);
}

TEST_F(FrameExplanationTest, WhereTwoObjectsMapsMarkAlikeThePoseThatFitsBetterHoldsTheSurface) {
  const Eigen::Isometry3f a = at(-0.046f, 0), c = at(0.046f, 0);  // touching boxes
  render({a, c});
  // A longer object posed over box a and part of c: it claims all of a's surface, a only part of
  // its. Maps from depth alone mark a region alike for both objects (they do not name objects);
  // a fits better.
  const ObjectModel long_box = prepareModel(boxMesh({0.144f, 0.055f, 0.035f}), {});
  const cv::Mat map_a = map(0, 0.8f), map_long = map(0, 0.8f) + map(1, 0.8f);
  InstancePose right = instance(a, 0.9f), wrong = instance(at(-0.019f, 0), 0.6f);
  std::vector<FramePose> poses = {{"a", 0, &box_, &map_a, &right},
                                  {"long", 0, &long_box, &map_long, &wrong}};
  explain(poses, {}, false);
  EXPECT_TRUE(right.accepted);
  EXPECT_FALSE(wrong.accepted);
  EXPECT_EQ(wrong.rejection, "explained by a 0");
}

TEST_F(FrameExplanationTest, TwoSeparateObjectsAreBothKept) {
  const Eigen::Isometry3f a = at(-0.07f, 0), b = at(0.07f, 0.02f);
  render({a, b});
  const cv::Mat map_a = map(0, 0.9f), map_b = map(1, 0.8f);
  InstancePose pa = instance(a, 0.6f), pb = instance(b, 0.99f);
  std::vector<FramePose> poses = {{"a", 0, &box_, &map_a, &pa}, {"b", 0, &box_, &map_b, &pb}};
  pa.evidence.explained = 0.3f;  // from an earlier frame: counted again
  explain(poses);
  EXPECT_TRUE(pa.accepted);
  EXPECT_TRUE(pb.accepted);
  EXPECT_EQ(pa.evidence.explained, 0.0f);
  EXPECT_EQ(pb.evidence.explained, 0.0f);
}

TEST_F(FrameExplanationTest, OnlyAcceptedPosesExplainAndDisabledChangesNothing) {
  const Eigen::Isometry3f pose = test::viewingPose(0.6f);
  render({pose});
  const cv::Mat box_map = map(0, 0.9f), small_map = map(0, 0.7f);
  InstancePose box = instance(pose, 0.2f), small = instance(pose, 0.95f);
  box.accepted = false;  // below min_confidence: it explains nothing
  box.rejection = "confidence";
  std::vector<FramePose> poses = {{"box", 0, &box_, &box_map, &box},
                                  {"small_box", 0, &small_box_, &small_map, &small}};
  // Without the objects' maps, which would give the box's surface to the box (below).
  explainPoses(poses, FreeSpaceCheck(cloud_, camera_, FreeSpaceParams{}), {});
  EXPECT_TRUE(small.accepted);
  EXPECT_EQ(box.rejection, "confidence");
  box.accepted = true;
  FrameExplanationParams off;
  off.enabled = false;
  explain(poses, off);
  EXPECT_TRUE(small.accepted);
}

TEST(FrameExplanationParams, RejectsAShareOutsideZeroToOne) {
  FrameExplanationParams params;
  params.max_explained_share = 1.5f;
  test::expectInputError([&] { params.validate(); }, "max_explained_share");
}

// A bin asked for one box: the absent look-alike is posed on a box that has no pose, where the
// box's map is higher than its own. The map gives that surface to the box; maps from depth alone,
// which mark every region of its size alike, do not.
TEST_F(FrameExplanationTest, APoseOnSurfaceAnotherObjectsMapHoldsIsClaimedByThatMap) {
  const Eigen::Isometry3f a = at(-0.046f, 0), b = at(0.046f, 0);  // touching boxes
  render({a, b});
  const cv::Mat bin = map(0, 0.9f) + map(1, 0.9f), small_map = map(1, 0.7f);
  for (const bool maps_name_objects : {true, false}) {
    InstancePose box = instance(a, 0.9f), small = instance(b, 0.95f);
    std::vector<FramePose> poses = {{"box", 0, &box_, &bin, &box},
                                    {"small_box", 0, &small_box_, &small_map, &small}};
    const std::vector<ObjectMap> maps = {{"box", &bin}, {"small_box", &small_map}};
    const std::vector<ExplainedPose> explained = explainPoses(
        poses, FreeSpaceCheck(cloud_, camera_, FreeSpaceParams{}), {}, maps_name_objects, maps);
    EXPECT_TRUE(explained.empty()) << maps_name_objects;  // no pose explains it
    EXPECT_TRUE(box.accepted) << maps_name_objects;
    EXPECT_EQ(small.accepted, !maps_name_objects);
    if (maps_name_objects) {
      EXPECT_EQ(small.rejection, "claimed by the map of box");
    }
  }
}

// Another object's map claims a pose's surface when it is higher there on the whole (its mean over
// the pose's pixels): a neighbour's map bleeding over a third of it, or a confusion weaker than the
// object's own map, leaves the pose.
TEST_F(FrameExplanationTest, AnotherMapClaimsThePoseOnlyWhereItIsHigherOnTheWhole) {
  const Eigen::Isometry3f pose = test::viewingPose(0.6f);
  render({pose});
  const cv::Mat box_map = map(0, 0.8f);
  const cv::Rect box = cv::boundingRect(labels_ == 1);
  cv::Mat bleeding(labels_.size(), CV_32FC1, cv::Scalar(0));
  bleeding(cv::Rect(box.x, box.y, box.width / 3, box.height)).setTo(0.9f);
  struct Case {
    cv::Mat other;
    bool kept;
  };
  for (const Case& c :
       {Case{bleeding, true}, Case{map(0, 0.7f), true}, Case{map(0, 0.9f), false}}) {
    InstancePose right = instance(pose, 0.9f);
    std::vector<FramePose> poses = {{"box", 0, &box_, &box_map, &right}};
    explainPoses(poses, FreeSpaceCheck(cloud_, camera_, FreeSpaceParams{}), {}, true,
                 {{"box", &box_map}, {"other", &c.other}});
    EXPECT_EQ(right.accepted, c.kept) << cv::mean(c.other)[0];
  }
}

}  // namespace
}  // namespace stocs
