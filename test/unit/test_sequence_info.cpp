// scene_events.json, the sidecar of a sequence: written and read back, bad files refused naming the
// file and the problem, and the rate of a dataset's sequences.
#include <gtest/gtest.h>

#include <fstream>

#include "stocs/sim/sequence_info.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {
namespace fs = std::filesystem;

std::string errorOf(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
  try {
    readSequenceInfo(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(SequenceInfo, IsReadBackAsWritten) {
  const fs::path file = test::scratchDir("sequence_info") / "scene_events.json";
  SequenceInfo info = evenlyTimed({1, 2, 3, 4, 5}, 30);
  info.events.push_back({SequenceEventKind::kRemoval, 2, 3, 14});
  writeSequenceInfo(file, info);
  const SequenceInfo read = readSequenceInfo(file);
  EXPECT_DOUBLE_EQ(read.rate_hz, 30);
  ASSERT_EQ(read.stamps.size(), 5u);
  EXPECT_DOUBLE_EQ(read.stamps.at(1), 0);
  EXPECT_NEAR(read.stamps.at(5), 4 / 30.0, 1e-6);
  ASSERT_EQ(read.events.size(), 1u);
  EXPECT_EQ(read.events[0].kind, SequenceEventKind::kRemoval);
  EXPECT_EQ(read.events[0].obj_id, 14);
  EXPECT_EQ(read.events[0].first_frame, 2);
  EXPECT_EQ(read.events[0].last_frame, 3);
}

TEST(SequenceInfo, BadFilesNameTheFileAndTheProblem) {
  const fs::path file = test::scratchDir("sequence_info_bad") / "scene_events.json";
  const std::string stamps = R"("stamps": {"0": 0, "1": 0.1})";
  EXPECT_NE(errorOf(file, "{").find(file.string() + ": not a sequence's scene_events.json"),
            std::string::npos);
  EXPECT_NE(errorOf(file, R"({"rate_hz": 0, "events": [], )" + stamps + "}")
                .find("rate_hz 0 is not a positive frame rate"),
            std::string::npos);
  EXPECT_NE(errorOf(file, R"({"rate_hz": 30, "events": [], "stamps": {"0": 0, "1": 0}})")
                .find("the time of image 1 (0 s) does not follow the one before"),
            std::string::npos);
  EXPECT_NE(errorOf(file, R"({"rate_hz": 30, "events": [], "stamps": {"x": 0}})")
                .find("a key of 'stamps' is not an image id"),
            std::string::npos);
  EXPECT_NE(errorOf(file, R"({"rate_hz": 30, )" + stamps +
                              R"(, "events": [{"kind": "spin", "obj_id": 1, "first_frame": 0,
                              "last_frame": 1}]})")
                .find("unknown event kind 'spin'"),
            std::string::npos);
  EXPECT_NE(errorOf(file, R"({"rate_hz": 30, )" + stamps +
                              R"(, "events": [{"kind": "push", "obj_id": 1, "first_frame": 5,
                              "last_frame": 1}]})")
                .find("the push event ends (frame 1) before it starts (frame 5)"),
            std::string::npos);
}

TEST(SequenceInfo, RateOfADatasetsSequencesMustAgree) {
  const fs::path root = test::scratchDir("sequence_rate");
  fs::create_directories(root / "models");
  for (const char* scene : {"000000", "000001", "000002"}) {
    fs::create_directories(root / "test" / scene);
  }
  const BopDataset ds(root);
  EXPECT_FALSE(sequenceRate(ds, {0, 1, 2}).has_value());
  writeSequenceInfo(sequenceInfoPath(ds.sceneDir(1)), evenlyTimed({0, 1}, 15));
  EXPECT_EQ(sequenceRate(ds, {0, 1, 2}), 15.0);
  writeSequenceInfo(sequenceInfoPath(ds.sceneDir(2)), evenlyTimed({0, 1}, 30));
  EXPECT_EQ(sequenceRate(ds, {0, 1}), 15.0);
  EXPECT_THROW(sequenceRate(ds, {0, 1, 2}), InputError);
}

}  // namespace
}  // namespace stocs
