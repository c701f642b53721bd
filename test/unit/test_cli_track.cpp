// `stocs estimate --track true` end to end: the images of a generated scene in im_id order as one
// stream, BOP results with the time of each image, each object's state in the log; an occluded
// object held rather than followed off; and the options tracking cannot honour.
#include <gtest/gtest.h>

#include <map>
#include <regex>

#include "stocs/io/bop_results.h"
#include "stocs/sim/sequence_info.h"
#include "test_support.h"

namespace stocs {
namespace {

const std::string kTool = STOCS_TOOL_PATH;

TEST(CliTrack, TracksTheImagesOfASceneInOrderAndWritesTheirTimes) {
  const auto root = test::scratchDir("cli_track");
  const std::filesystem::path data = root / "data", results = root / "r.csv";
  std::string out;
  ASSERT_EQ(test::runCommand(kTool + " synth --out " + data.string() +
                                 " --images 3 --objects 3 --absent 0 --seed 1 --quiet",
                             out),
            0)
      << out;
  ASSERT_EQ(test::runCommand(kTool + " estimate --dataset " + data.string() + " --out " +
                                 results.string() + " --cache-dir " + (root / "cache").string() +
                                 " --track true",
                             out),
            0)
      << out;
  // Every object of every image gets a pose within 10% of its diameter, with its state.
  const std::regex line(
      R"(scene 0 image (\d) object \d: segment \d+ points, (tracked|redetected), .*\(([0-9.]+)% of diameter\))");
  int poses = 0;
  for (auto it = std::sregex_iterator(out.begin(), out.end(), line); it != std::sregex_iterator();
       ++it) {
    ++poses;
    EXPECT_LT(std::stod((*it)[3]), 10.0) << it->str();
  }
  EXPECT_EQ(poses, 9) << out;
  EXPECT_NE(out.find("tracking: "), std::string::npos) << out;
  // One row per (image, object), each image's rows with the image's time.
  std::map<int, double> image_time;
  const std::vector<BopResult> rows = readBopResults(results);
  ASSERT_EQ(rows.size(), 9u);
  for (const BopResult& r : rows) {
    EXPECT_GT(r.time, 0);
    const auto [it, fresh] = image_time.emplace(r.im_id, r.time);
    if (!fresh) {
      EXPECT_EQ(it->second, r.time);
    }
  }
  EXPECT_EQ(image_time.size(), 3u);
}

// The ROS tests' sequence (StocsRosTests.cmake): an occluder passes in front of the bowl in
// frames 17-21, leaving a few hundred of its points in view, which fit poses moved or sunk behind
// its visible surface. Whatever each seed's search finds there, no pose of the bowl is published
// more than 5% of its diameter off while it is hidden or after.
TEST(CliTrack, AnObjectAnOccluderHidesIsNeverPublishedOffItsSurface) {
  const auto root = test::scratchDir("cli_track_occluded");
  const std::filesystem::path data = root / "data";
  std::string out;
  ASSERT_EQ(test::runCommand(kTool + " synth --out " + data.string() +
                                 " --sequence --frames 24 --objects 3 --distractors 1 --width 320"
                                 " --height 240 --fx 307.5 --fy 307.5 --cx 159.5 --cy 119.5"
                                 " --push-start 2 --push-frames 4 --lift-start 6 --lift-frames 4"
                                 " --removal-start 10 --removal-frames 6 --occlusion-start 17"
                                 " --occlusion-frames 5 --seed 3 --quiet",
                             out),
            0)
      << out;
  int occluded = -1;
  for (const SequenceEvent& e : readSequenceInfo(data / "test/000000/scene_events.json").events) {
    if (e.kind == SequenceEventKind::kOcclusion) occluded = e.obj_id;
  }
  ASSERT_GT(occluded, 0);
  const std::regex line(
      R"(scene 0 image (\d+) object (\d+): segment \d+ points, (tracked|redetected), .*\(([0-9.]+)% of diameter\))");
  for (const int seed : {1, 2, 3}) {
    ASSERT_EQ(test::runCommand(kTool + " estimate --dataset " + data.string() + " --out " +
                                   (root / "r.csv").string() + " --cache-dir " +
                                   (root / "cache").string() + " --track true --seed " +
                                   std::to_string(seed),
                               out),
              0)
        << out;
    int published = 0;
    for (auto it = std::sregex_iterator(out.begin(), out.end(), line); it != std::sregex_iterator();
         ++it) {
      if (std::stoi((*it)[2]) != occluded || std::stoi((*it)[1]) < 17) continue;
      ++published;
      EXPECT_LT(std::stod((*it)[4]), 5.0) << "seed " << seed << ": " << it->str();
    }
    EXPECT_GE(published, 4) << "seed " << seed << ": the object was not followed again\n" << out;
  }
}

TEST(CliTrack, OptionsTrackingCannotHonourExitTwo) {
  const auto root = test::scratchDir("cli_track_bad");
  const std::filesystem::path data = root / "data";
  test::writeSyntheticBopDataset(data);
  const std::string estimate = kTool + " estimate --dataset " + data.string() + " --out " +
                               (root / "r.csv").string() + " --no-cache --track true ";
  std::string out;
  EXPECT_EQ(test::runCommand(estimate + "--repeats 2", out), 2);
  EXPECT_NE(out.find("--repeats 2 would track the same image again"), std::string::npos) << out;
  EXPECT_EQ(test::runCommand(estimate + "--method ppf", out), 2);
  EXPECT_NE(out.find("--method ppf cannot track"), std::string::npos) << out;
  EXPECT_EQ(test::runCommand(estimate + "--max-gap 0", out), 2);
  EXPECT_NE(out.find("--max-gap 0 s is outside (0, 3600]"), std::string::npos) << out;
}

}  // namespace
}  // namespace stocs
