// BOP targets files (test_targets_bop19.json): round trip, and every malformed entry named.
#include <gtest/gtest.h>

#include "stocs/io/bop_targets.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

/// The message of the InputError that parsing `text` throws ("" when none).
std::string parseError(const std::string& text) {
  try {
    parseBopTargets(text, "t.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(BopTargets, WrittenTargetsReadBackWithAbsentOnes) {
  const auto file = test::scratchDir("bop_targets") / "test_targets_bop19.json";
  const std::vector<BopTarget> written = {{1, 0, 2, 1}, {1, 0, 5, 0}, {2, 3, 1, 3}};
  writeBopTargets(file, written);
  const std::vector<BopTarget> read = readBopTargets(file);
  ASSERT_EQ(read.size(), written.size());
  for (size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].scene_id, written[i].scene_id);
    EXPECT_EQ(read[i].im_id, written[i].im_id);
    EXPECT_EQ(read[i].obj_id, written[i].obj_id);
    EXPECT_EQ(read[i].inst_count, written[i].inst_count);
  }
  EXPECT_TRUE(parseBopTargets("[]", "t.json").empty());
}

TEST(BopTargets, MalformedFilesNameTheFileTheEntryAndTheProblem) {
  const std::string ok = R"({"scene_id": 1, "im_id": 0, "obj_id": 2, "inst_count": 1})";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"[", "t.json: invalid JSON"},
      {R"({"scene_id": 1})",
       "t.json: a targets file is a list of {scene_id, im_id, obj_id, "
       "inst_count}; this is a JSON object"},
      {"[" + ok + ", 3]", "t.json: entry 1 is a JSON number, not an object"},
      {R"([{"scene_id": 1, "im_id": 0, "inst_count": 1}])",
       "t.json: entry 0: missing key 'obj_id'"},
      {"[" + ok + R"(, {"scene_id": 1, "im_id": 0, "obj_id": 3, "inst_count": -1}])",
       "t.json: entry 1: 'inst_count' is -1; it must be an integer of at least 0"},
      {R"([{"scene_id": "1", "im_id": 0, "obj_id": 2, "inst_count": 1}])",
       "t.json: entry 0: 'scene_id' is \"1\"; it must be an integer of at least 0"},
      {R"([{"scene_id": 1, "im_id": 0.5, "obj_id": 2, "inst_count": 1}])",
       "t.json: entry 0: 'im_id' is 0.5; it must be an integer of at least 0"},
      {R"([{"scene_id": 1, "im_id": 0, "obj_id": 0, "inst_count": 1}])",
       "t.json: entry 0: 'obj_id' is 0; it must be an integer of at least 1"},
      {R"([{"scene_id": 1, "im_id": 0, "obj_id": 2, "inst_count": 1e12}])",
       "t.json: entry 0: 'inst_count' is 1000000000000.0; it must be an integer of at least 0"},
      {R"([{"scene_id": 1, "im_id": 0, "obj_id": 2, "inst_count": 99999999999}])",
       "t.json: entry 0: 'inst_count' is 99999999999; it must be an integer of at least 0"},
      {"[" + ok + ", " + ok + "]", "t.json: entry 1 repeats scene 1 image 0 object 2 of entry 0"},
  };
  for (const auto& [text, message] : cases) {
    const std::string error = parseError(text);
    EXPECT_NE(error.find(message), std::string::npos) << text << "\n  gave: " << error;
  }
  try {
    readBopTargets(test::scratchDir("bop_targets_missing") / "none.json");
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("none.json"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stocs
