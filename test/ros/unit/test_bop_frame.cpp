// The scene publisher's frame loading with each probability source: the dataset's prob/ maps, and
// the simulator `stocs estimate --prob sim:PRESET` uses where a dataset has none.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/core.hpp>

#include "stocs/io/bop_dataset.h"
#include "stocs/sim/probability_source.h"
#include "stocs_ros/scene_publisher/bop_frame.h"
#include "test_support.h"

namespace stocs_ros {
namespace {

class BopFrameLoading : public ::testing::Test {
 protected:
  /// The generated box frame (object 1), without its prob/ map when `with_map` is false.
  static stocs::BopDataset dataset(bool with_map) {
    const std::filesystem::path root =
        stocs::test::scratchDir(with_map ? "bop_frame_maps" : "bop_frame_no_maps") / "data";
    stocs::test::writeSyntheticBopDataset(root);
    if (!with_map) std::filesystem::remove_all(root / "test" / "000000" / "prob");
    return stocs::BopDataset(root);
  }

  /// Image 0 of scene 0 with objects 1 (the box) and 2 (not in the frame).
  static BopFrame load(const stocs::BopDataset& data, const std::string& spec) {
    const auto source = stocs::makeProbabilitySource(spec, data, 0);
    return loadBopFrame(data, 0, 0, data.sceneCameras(0).at(0), {1, 2}, *source);
  }

  /// Mean probability on the box's pixels (where the depth has a measurement) and elsewhere.
  static std::pair<double, double> meanOnAndOffTheBox(const BopFrame& frame, size_t object) {
    const cv::Mat on_box = frame.depth == frame.depth;  // NaN where nothing was measured
    return {cv::mean(frame.probabilities[object], on_box)[0],
            cv::mean(frame.probabilities[object], ~on_box)[0]};
  }
};

TEST_F(BopFrameLoading, RealMapsAreAllZeroWhereTheDatasetHasNoneAndTheObjectsAreNamed) {
  const BopFrame frame = load(dataset(false), "real");
  ASSERT_EQ(frame.probabilities.size(), 2u);
  EXPECT_EQ(cv::countNonZero(frame.probabilities[0]), 0);
  EXPECT_EQ(cv::countNonZero(frame.probabilities[1]), 0);
  EXPECT_EQ(frame.objects_without_map, (std::vector<int>{1, 2}));
}

TEST_F(BopFrameLoading, SimulatedMapsFollowTheGroundTruthAsTheCliDraws) {
  const stocs::BopDataset data = dataset(false);
  const BopFrame frame = load(data, "sim:mild");
  ASSERT_EQ(frame.probabilities.size(), 2u);
  const auto [on_box, off_box] = meanOnAndOffTheBox(frame, 0);
  EXPECT_GT(on_box, 0.5);
  EXPECT_LT(off_box, 0.1);
  // Object 2 is not in the frame: no map, as a network would give none.
  EXPECT_EQ(cv::countNonZero(frame.probabilities[1]), 0);
  EXPECT_EQ(frame.objects_without_map, (std::vector<int>{2}));
  // The same map as `stocs estimate --prob sim:mild --seed 0` estimates on.
  const cv::Mat cli = stocs::makeProbabilitySource("sim:mild", data, 0)->load(0, 0, 1);
  EXPECT_EQ(cv::countNonZero(frame.probabilities[0] != cli), 0);
}

TEST_F(BopFrameLoading, SimulationKeepsTheDatasetsRealMaps) {
  const stocs::BopDataset data = dataset(true);
  const BopFrame frame = load(data, "sim:mild");
  EXPECT_EQ(cv::countNonZero(frame.probabilities[0] != data.loadProbability(0, 0, 1)), 0);
  EXPECT_EQ(frame.objects_without_map, (std::vector<int>{2}));
}

}  // namespace
}  // namespace stocs_ros
