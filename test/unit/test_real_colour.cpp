// Colour on real data: the YCB-Video models of ycbv-0000 coloured by `stocs colour-models` from
// frames 1 and 2, then the colour agreement at the ground-truth pose in the unseen frames 3..5,
// against the same pose turned half a turn about each of the model's principal axes (the
// near-symmetric poses depth alone cannot tell apart).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <chrono>
#include <fstream>
#include <opencv2/core.hpp>

#include "stocs/estimation/stages/colour_agreement.h"
#include "stocs/eval/pose_metrics.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/io/bop_results.h"
#include "stocs/model/model_cache.h"
#include "test_support.h"

namespace stocs {
namespace {

/// The model's principal axes (columns), about its sample centre.
Eigen::Matrix3f principalAxes(const ObjectModel& model) {
  const Eigen::Vector3f centre = sampleCentre(model);
  Eigen::Matrix3f scatter = Eigen::Matrix3f::Zero();
  for (const Eigen::Vector3f& p : model.points) scatter += (p - centre) * (p - centre).transpose();
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f>(scatter).eigenvectors();
}

/// `pose` turned half a turn about `axis` (model frame) through the sample centre.
Eigen::Isometry3f turned(const Eigen::Isometry3f& pose, const Eigen::Vector3f& axis,
                         const Eigen::Vector3f& centre) {
  const Eigen::Isometry3f turn = Eigen::Translation3f(centre) *
                                 Eigen::AngleAxisf(static_cast<float>(M_PI), axis) *
                                 Eigen::Translation3f(-centre);
  return pose * turn;
}

/// Colours ycbv-0000's models from frames 1 and 2 into `scratch`/models, and links its images
/// there, so that `scratch` is a dataset with coloured models.
void colourYcbModels(const std::filesystem::path& data, const std::filesystem::path& scratch) {
  std::string out;
  ASSERT_EQ(test::runCommand(std::string(STOCS_TOOL_PATH) + " colour-models --dataset " +
                                 (data / "ycbv-0000").string() + " --images 0/1,0/2 --out " +
                                 scratch.string(),
                             out),
            0)
      << out;
  std::filesystem::remove(scratch / "test");
  std::filesystem::create_directory_symlink(std::filesystem::absolute(data / "ycbv-0000" / "test"),
                                            scratch / "test");
}

TEST(RealColour, TheTruthAgreesBetterThanItsHalfTurnsInUnseenYcbFrames) {
  STOCS_REQUIRE_DATASETS(data);
  const std::filesystem::path scratch = test::scratchDir("real_colour");
  colourYcbModels(data, scratch);
  const BopDataset ds(data / "ycbv-0000");
  const ModelCache cache(scratch / "cache");
  const auto gt = ds.sceneGroundTruth(0);
  const auto cameras = ds.sceneCameras(0);
  int better = 0, compared = 0;
  double seconds = 0;
  int calls = 0;
  for (int im = 3; im <= 5; ++im) {
    const cv::Mat depth = ds.loadDepth(0, im);
    const cv::Mat bgr = ds.loadColour(0, im, depth.size());
    const CameraIntrinsics k = cameras.at(im).intrinsics(depth.cols, depth.rows);
    const OrganizedCloud cloud = cloudFromDepth(depth, k, cameras.at(im).depth_scale / 1000);
    const FreeSpaceCheck visibility(cloud, k, FreeSpaceParams{});
    for (const BopGtInstance& g : gt.at(im)) {
      const PreparedModel m =
          cache.load((scratch / "models" / ds.modelPath(g.obj_id).filename()).string(), 0.001f,
                     ModelPreparationParams{});
      Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
      pose.linear() = g.R.cast<float>();
      pose.translation() = (g.t_mm / 1000).cast<float>();
      const auto start = std::chrono::steady_clock::now();
      const ColourAgreement truth = colourAgreement(m.model, pose, visibility, &bgr);
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      ++calls;
      std::cout << "image " << im << " object " << g.obj_id << " (" << m.model.size()
                << " samples): truth " << truth.agreement << " (" << truth.samples << ")";
      const Eigen::Matrix3f axes = principalAxes(m.model);
      for (int a = 0; a < 3; ++a) {
        const ColourAgreement half = colourAgreement(
            m.model, turned(pose, axes.col(a), sampleCentre(m.model)), visibility, &bgr);
        std::cout << ", half turn " << a << ": " << half.agreement << " (" << half.samples << ")";
        if (!truth.evidence || !half.evidence) continue;
        ++compared;
        better += truth.agreement > half.agreement;
      }
      std::cout << "\n";
      EXPECT_TRUE(truth.evidence) << "image " << im << " object " << g.obj_id;
    }
  }
  std::cout << "colour agreement: " << 1000 * seconds / calls << " ms per pose\n";
  std::cout << "truth better than the half turn in " << better << " of " << compared << "\n";
  EXPECT_GT(compared, 0);
  EXPECT_GE(10 * better, 9 * compared);
}

// The gelatin box turned over and the foam brick turned a quarter fit the depth alike; the models'
// colour, seen in frames 1 and 2 on one side only, tells the turn in frames 3 to 5, where only some
// turns show coloured surface and the point model's holes lower the truth's objective.
TEST(RealColour, TheGelatinBoxAndFoamBrickFaceTheRightWayInUnseenYcbFrames) {
  STOCS_REQUIRE_DATASETS(data);
  const std::filesystem::path scratch = test::scratchDir("real_colour_poses");
  colourYcbModels(data, scratch);
  {
    std::ofstream targets(scratch / "targets.json");
    targets << "[";
    for (int im = 3; im <= 5; ++im) {
      for (const int obj : {8, 21}) {
        targets << (im == 3 && obj == 8 ? "" : ",") << R"({"scene_id": 0, "im_id": )" << im
                << R"(, "obj_id": )" << obj << R"(, "inst_count": 1})";
      }
    }
    targets << "]";
  }
  std::string out;
  ASSERT_EQ(test::runCommand(std::string(STOCS_TOOL_PATH) + " estimate --dataset " +
                                 scratch.string() + " --prob sim:mild --seed 1 --targets " +
                                 (scratch / "targets.json").string() + " --out " +
                                 (scratch / "poses.csv").string() + " --cache-dir " +
                                 (scratch / "cache").string(),
                             out),
            0)
      << out;
  const BopDataset ds(scratch);
  const ModelCache cache(scratch / "cache");
  const auto gt = ds.sceneGroundTruth(0);
  int right = 0, posed = 0;
  for (const BopResult& r : readBopResults(scratch / "poses.csv")) {
    ++posed;
    const PreparedModel m =
        cache.load((scratch / "models" / ds.modelPath(r.obj_id).filename()).string(), 0.001f,
                   ModelPreparationParams{});
    for (const BopGtInstance& g : gt.at(r.im_id)) {
      if (g.obj_id != r.obj_id) continue;
      std::vector<Eigen::Vector3f> points_mm;
      for (const Eigen::Vector3f& p : m.model.points) points_mm.push_back(1000 * p);
      const double add = addError(points_mm, RigidPose{r.R, r.t_mm}, RigidPose{g.R, g.t_mm});
      std::cout << "image " << r.im_id << " object " << r.obj_id << ": ADD " << add << " mm\n";
      right += add < 100 * m.model.diameter;  // 10% of the diameter, in mm
    }
  }
  EXPECT_EQ(posed, 6);
  EXPECT_GE(right, 5) << out;
}

}  // namespace
}  // namespace stocs
