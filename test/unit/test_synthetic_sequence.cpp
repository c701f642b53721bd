// Generated sequences (`stocs synth --sequence`): a smooth camera path within its speed limits,
// object events in their frame ranges (a removed object leaves the ground truth, an occluded one
// loses visibility, pushed and lifted ones move only then), the sidecar scene_events.json, the
// same files for a seed, and refusal of bad options.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "stocs/io/bop_dataset.h"
#include "stocs/io/bop_targets.h"
#include "stocs/sim/camera_path.h"
#include "stocs/sim/sequence_info.h"
#include "stocs/sim/synthetic_dataset.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {
namespace fs = std::filesystem;

/// 40 frames at a quarter of the default resolution, each event a few frames long.
SyntheticDatasetParams shortSequence(uint64_t seed) {
  SyntheticDatasetParams p;
  p.layout.objects = 5;
  p.layout.distractors = 1;
  p.camera = {307.5, 307.5, 159.5, 119.5, 320, 240};
  p.absent_per_image = 1;
  p.seed = seed;
  SequenceParams& s = p.sequence;
  s.enabled = true;
  s.frames = 40;
  s.push_start = 2;
  s.push_frames = 8;
  s.lift_start = 10;
  s.lift_frames = 9;
  s.removal_start = 20;
  s.removal_frames = 6;
  s.occlusion_start = 28;
  s.occlusion_frames = 10;
  return p;
}

class SyntheticSequence : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(test::scratchDir("sequence"));
    writeSyntheticDataset(*root_, shortSequence(5));
  }
  static void TearDownTestSuite() { delete root_; }

  static const SequenceEvent& event(const SequenceInfo& info, SequenceEventKind kind) {
    for (const SequenceEvent& e : info.events) {
      if (e.kind == kind) return e;
    }
    throw std::runtime_error("no such event");
  }

  static fs::path* root_;
};
fs::path* SyntheticSequence::root_ = nullptr;

Eigen::Isometry3d pose(const BopGtInstance& g) {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.linear() = g.R;
  p.translation() = g.t_mm / 1000;
  return p;
}

const BopGtInstance* find(const std::vector<BopGtInstance>& gt, int obj_id) {
  for (const BopGtInstance& g : gt) {
    if (g.obj_id == obj_id) return &g;
  }
  return nullptr;
}

TEST(CameraPath, StepsStayWithinTheSpeedLimitsAndReachOne) {
  SceneLayoutParams layout;
  Rng rng(3);
  const CameraPathLimits limits{30, 0.15f, 0.5f};
  const std::vector<Eigen::Isometry3f> path = smoothCameraPath(layout, 300, limits, rng);
  ASSERT_EQ(path.size(), 300u);
  double fastest = 0, fastest_turn = 0;
  for (size_t i = 1; i < path.size(); ++i) {
    const double move =
        (path[i].inverse().translation() - path[i - 1].inverse().translation()).norm();
    const double turn = rotationAngle(path[i], path[i - 1]);
    EXPECT_LE(move, limits.translation_speed / limits.rate_hz * (1 + 1e-5)) << "frame " << i;
    EXPECT_LE(turn, limits.rotation_speed / limits.rate_hz * (1 + 1e-5)) << "frame " << i;
    fastest = std::max(fastest, move * limits.rate_hz / limits.translation_speed);
    fastest_turn = std::max(fastest_turn, turn * limits.rate_hz / limits.rotation_speed);
  }
  // The path is not slower than it need be: one limit is nearly reached.
  EXPECT_GT(std::max(fastest, fastest_turn), 0.98);
  for (const Eigen::Isometry3f& camera : path) {
    // Always looking at the table: its centre is in front, near the middle of the image.
    const Eigen::Vector3f centre = camera * Eigen::Vector3f(0, 0, 0.03f);
    EXPECT_GT(centre.z(), layout.min_distance * 0.9f);
    EXPECT_LT(std::hypot(centre.x(), centre.y()) / centre.z(), 0.1f);
  }
  Rng still(3);
  const std::vector<Eigen::Isometry3f> held = smoothCameraPath(layout, 5, {30, 0, 0.5f}, still);
  EXPECT_TRUE(held[4].isApprox(held[0]));
}

TEST_F(SyntheticSequence, FramesAreTimedInImageOrderWithEveryEventInTheSidecar) {
  const BopDataset ds(*root_);
  const SequenceInfo info = readSequenceInfo(sequenceInfoPath(ds.sceneDir(0)));
  EXPECT_DOUBLE_EQ(info.rate_hz, 30);
  ASSERT_EQ(info.stamps.size(), 40u);
  for (const auto& [im, t] : info.stamps) EXPECT_NEAR(t, im / 30.0, 1e-6);
  ASSERT_EQ(info.events.size(), 4u);
  EXPECT_EQ(event(info, SequenceEventKind::kRemoval).first_frame, 20);
  EXPECT_EQ(event(info, SequenceEventKind::kRemoval).last_frame, 25);
  EXPECT_EQ(event(info, SequenceEventKind::kOcclusion).last_frame, 37);
  // Five objects, four events: each event has an object of its own.
  std::set<int> objects;
  for (const SequenceEvent& e : info.events) objects.insert(e.obj_id);
  EXPECT_EQ(objects.size(), 4u);
  EXPECT_EQ(ds.sceneGroundTruth(0).size(), 40u);
}

TEST_F(SyntheticSequence, RemovedObjectLeavesTheGroundTruthAndStaysATarget) {
  const BopDataset ds(*root_);
  const SequenceEvent removal =
      event(readSequenceInfo(sequenceInfoPath(ds.sceneDir(0))), SequenceEventKind::kRemoval);
  const std::map<int, std::vector<BopGtInstance>> gt = ds.sceneGroundTruth(0);
  std::map<int, int> listed_count;
  for (const BopTarget& t : readBopTargets(*root_ / "test_targets_bop19.json")) {
    if (t.obj_id == removal.obj_id) listed_count[t.im_id] = t.inst_count;
  }
  for (const auto& [im, instances] : gt) {
    const bool out = im >= removal.first_frame && im <= removal.last_frame;
    EXPECT_EQ(find(instances, removal.obj_id) == nullptr, out) << "image " << im;
    ASSERT_TRUE(listed_count.count(im)) << "image " << im;
    EXPECT_EQ(listed_count.at(im), out ? 0 : 1) << "image " << im;
  }
  // Put back where it stood.
  const Eigen::Isometry3d before = pose(*find(gt.at(removal.first_frame - 1), removal.obj_id));
  const Eigen::Isometry3d after = pose(*find(gt.at(removal.last_frame + 1), removal.obj_id));
  const BopGtInstance* other = nullptr;
  for (const BopGtInstance& g : gt.at(0)) {
    if (g.obj_id != removal.obj_id) other = &g;
  }
  ASSERT_NE(other, nullptr);
  // Relative to a still object, so that the camera's motion drops out.
  const auto relative = [&](int im, const Eigen::Isometry3d& p) -> Eigen::Vector3d {
    return (pose(*find(gt.at(im), other->obj_id)).inverse() * p).translation();
  };
  EXPECT_LT(
      (relative(removal.first_frame - 1, before) - relative(removal.last_frame + 1, after)).norm(),
      1e-4);
}

TEST_F(SyntheticSequence, OccludedObjectLosesVisibilityWhileTheOccluderPasses) {
  const BopDataset ds(*root_);
  const SequenceEvent occlusion =
      event(readSequenceInfo(sequenceInfoPath(ds.sceneDir(0))), SequenceEventKind::kOcclusion);
  const nlohmann::json info =
      nlohmann::json::parse(readTextFile(ds.sceneDir(0) / "scene_gt_info.json"));
  const std::map<int, std::vector<BopGtInstance>> gt = ds.sceneGroundTruth(0);
  const auto visible = [&](int im) {
    const std::vector<BopGtInstance>& instances = gt.at(im);
    for (size_t i = 0; i < instances.size(); ++i) {
      if (instances[i].obj_id == occlusion.obj_id)
        return info.at(std::to_string(im)).at(i).at("visib_fract").get<double>();
    }
    return -1.0;
  };
  const int middle = (occlusion.first_frame + occlusion.last_frame) / 2;
  const double before = visible(occlusion.first_frame - 1), during = visible(middle);
  EXPECT_GT(before, 0.3);
  EXPECT_LT(during, before - 0.3) << "before " << before << ", during " << during;
}

TEST_F(SyntheticSequence, PushedAndLiftedObjectsMoveOnlyDuringTheirEvents) {
  const BopDataset ds(*root_);
  const SequenceInfo info = readSequenceInfo(sequenceInfoPath(ds.sceneDir(0)));
  const std::map<int, std::vector<BopGtInstance>> gt = ds.sceneGroundTruth(0);
  std::set<int> moving;
  for (const SequenceEvent& e : info.events) moving.insert(e.obj_id);
  int still = 0;
  for (const BopGtInstance& g : gt.at(0)) {
    if (!moving.count(g.obj_id)) still = g.obj_id;
  }
  ASSERT_GT(still, 0);
  // Position relative to the still object, metres.
  const auto where = [&](int im, int obj) -> Eigen::Vector3d {
    return (pose(*find(gt.at(im), still)).inverse() * pose(*find(gt.at(im), obj))).translation();
  };
  const SequenceParams& params = shortSequence(5).sequence;
  for (const auto& [kind, distance] : {std::pair{SequenceEventKind::kPush, params.push_distance},
                                       std::pair{SequenceEventKind::kLift, params.lift_distance}}) {
    const SequenceEvent e = event(info, kind);
    const Eigen::Vector3d start = where(0, e.obj_id), end = where(39, e.obj_id);
    for (int im = 0; im < 40; ++im) {
      const Eigen::Vector3d here = where(im, e.obj_id);
      if (im < e.first_frame) {
        EXPECT_LT((here - start).norm(), 1e-4) << "image " << im;
      }
      if (im >= e.last_frame) {
        EXPECT_LT((here - end).norm(), 1e-4) << "image " << im;
      }
    }
    EXPECT_NEAR((end - start).norm(), distance, 1e-3) << sequenceEventName(kind);
  }
  const SequenceEvent lift = event(info, SequenceEventKind::kLift);
  const int top = (lift.first_frame + lift.last_frame) / 2;
  // Up in the still object's frame is not known, but the lifted object is farther from it.
  EXPECT_GT((where(top, lift.obj_id) - where(0, lift.obj_id)).norm(), 0.5 * params.lift_height);
}

TEST(SyntheticSequenceFiles, SameSeedSameFilesAndStillCameraKeepsStillObjectsStill) {
  SyntheticDatasetParams p = shortSequence(9);
  p.sequence.frames = 6;
  p.sequence.push_frames = p.sequence.lift_frames = p.sequence.removal_frames =
      p.sequence.occlusion_frames = 0;
  const fs::path a = test::scratchDir("sequence_a"), b = test::scratchDir("sequence_b");
  writeSyntheticDataset(a, p);
  writeSyntheticDataset(b, p);
  std::set<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(a)) {
    if (!e.is_regular_file()) continue;
    const fs::path rel = fs::relative(e.path(), a);
    names.insert(rel.string());
    EXPECT_EQ(readTextFile(e.path()), readTextFile(b / rel)) << rel;
  }
  EXPECT_TRUE(names.count("test/000000/scene_events.json"));
  EXPECT_TRUE(names.count("test/000000/prob/000005_000001.png") ||
              names.count("test/000000/prob/000005_000002.png"));
  p.sequence.translation_speed = 0;
  const fs::path c = test::scratchDir("sequence_still");
  writeSyntheticDataset(c, p);
  const std::map<int, std::vector<BopGtInstance>> gt = BopDataset(c).sceneGroundTruth(0);
  for (size_t i = 0; i < gt.at(0).size(); ++i) {
    EXPECT_TRUE(pose(gt.at(5)[i]).isApprox(pose(gt.at(0)[i]), 1e-6));
  }
}

TEST(SyntheticSequenceFiles, BadOptionsAreRefusedNamingThem) {
  const auto refused = [](const SyntheticDatasetParams& p, const std::string& expected) {
    try {
      writeSyntheticDataset(test::scratchDir("sequence_bad"), p);
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      return;
    }
    ADD_FAILURE() << "accepted; expected an error naming " << expected;
  };
  SyntheticDatasetParams p = shortSequence(1);
  p.sequence.translation_speed = -0.1f;
  refused(p, "translation_speed");
  p = shortSequence(1);
  p.sequence.rotation_speed = -1;
  refused(p, "rotation_speed");
  p = shortSequence(1);
  p.sequence.rate_hz = 0;
  refused(p, "rate_hz");
  p = shortSequence(1);
  p.sequence.removal_start = 38;  // 6 frames from 38 end at 43, past frame 39
  refused(p, "the removal (--removal-start 38, --removal-frames 6) ends at frame 43");
  p = shortSequence(1);
  p.sequence.frames = 30;  // the occlusion, 28..37, no longer fits
  refused(p, "the occlusion");
  p = shortSequence(1);
  p.images_per_scene = 3;
  refused(p, "--frames");
  EXPECT_FALSE(fs::exists(test::scratchDir("sequence_bad") / "test"));
}

}  // namespace
}  // namespace stocs
