// The on-disk model cache: round trip, invalidation on change, and corruption handling.
#include <gtest/gtest.h>

#include <fstream>

#include "stocs/model/model_cache.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

class ModelCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratchDir("model_cache");
    model_file_ = (dir_ / "box.ply").string();
    writePly(model_file_, boxMesh({100, 60, 40}));
  }

  void expectSameModel(const PreparedModel& a, const PreparedModel& b) {
    ASSERT_EQ(a.model.size(), b.model.size());
    EXPECT_EQ(a.model.diameter, b.model.diameter);
    EXPECT_EQ(a.model.even_sampling, b.model.even_sampling);
    for (size_t i = 0; i < a.model.size(); ++i) {
      ASSERT_EQ(a.model.points[i], b.model.points[i]);
      ASSERT_EQ(a.model.normals[i], b.model.normals[i]);
    }
    EXPECT_EQ(a.ppf_map.pairCount(), b.ppf_map.pairCount());
    EXPECT_EQ(a.ppf_map.occupiedKeyCount(), b.ppf_map.occupiedKeyCount());
  }

  void corrupt(const std::filesystem::path& file, std::streamoff offset) {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(offset);
    char c = 0;
    f.read(&c, 1);
    f.seekp(offset);
    c = static_cast<char>(c ^ 0x5a);
    f.write(&c, 1);
  }

  std::filesystem::path dir_;
  std::string model_file_;
  ModelPreparationParams params_;
};

TEST_F(ModelCacheTest, BuildsThenLoadsTheSameModel) {
  const ModelCache cache(dir_ / "cache");
  CacheReport first, second;
  const PreparedModel a = cache.load(model_file_, 0.001f, params_, &first);
  EXPECT_EQ(first.outcome, CacheOutcome::kBuilt);
  EXPECT_TRUE(std::filesystem::exists(first.entry));
  const PreparedModel b = cache.load(model_file_, 0.001f, params_, &second);
  EXPECT_EQ(second.outcome, CacheOutcome::kLoaded);
  EXPECT_EQ(first.entry, second.entry);
  expectSameModel(a, b);
  expectSameModel(a, prepareModelFile(model_file_, 0.001f, params_));
}

TEST_F(ModelCacheTest, ParametersAndModelBytesSelectTheEntry) {
  const ModelCache cache(dir_ / "cache");
  const auto base = cache.entryPath(model_file_, 0.001f, params_);
  ModelPreparationParams other = params_;
  other.ppf.angle_step_deg = 12;
  EXPECT_NE(cache.entryPath(model_file_, 0.001f, other), base);
  EXPECT_NE(cache.entryPath(model_file_, 0.0011f, params_), base);
  std::ofstream(model_file_, std::ios::app) << "\n";  // same geometry, other bytes
  EXPECT_NE(cache.entryPath(model_file_, 0.001f, params_), base);
  EXPECT_EQ(base.parent_path(), dir_ / "cache");
}

// A glTF's geometry is usually in a buffer file of its own: changing it must change the entry.
TEST_F(ModelCacheTest, AGltfBufferFileSelectsTheEntry) {
  const std::filesystem::path gltf = dir_ / "triangle.gltf";
  std::ofstream(gltf) << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],)"
                      << R"( "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes":)"
                      << R"( {"POSITION": 0}}]}], "accessors": [{"bufferView": 0, "count": 3,)"
                      << R"( "type": "VEC3", "componentType": 5126}], "bufferViews": [{"buffer":)"
                      << R"( 0, "byteLength": 36}], "buffers": [{"byteLength": 36, "uri":)"
                      << R"( "triangle.bin"}]})";
  auto writeTriangle = [&](float size) {
    const float corners[9] = {0, 0, 0, size, 0, 0, 0, size, 0};
    std::ofstream(dir_ / "triangle.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(corners), sizeof corners);
  };
  const ModelCache cache(dir_ / "cache");
  writeTriangle(0.05f);
  const auto small = cache.entryPath(gltf.string(), 1.0f, params_);
  writeTriangle(0.08f);
  EXPECT_NE(cache.entryPath(gltf.string(), 1.0f, params_), small);
  CacheReport report;
  EXPECT_NEAR(cache.load(gltf.string(), 1.0f, params_, &report).model.diameter,
              0.08f * std::sqrt(2.0f), 1e-4f);
  EXPECT_EQ(report.outcome, CacheOutcome::kBuilt);
}

TEST_F(ModelCacheTest, CorruptPayloadIsDetectedAndRebuilt) {
  const ModelCache cache(dir_ / "cache");
  CacheReport report;
  const PreparedModel a = cache.load(model_file_, 0.001f, params_, &report);
  const auto size = std::filesystem::file_size(report.entry);
  corrupt(report.entry, static_cast<std::streamoff>(size / 2));
  const PreparedModel b = cache.load(model_file_, 0.001f, params_, &report);
  EXPECT_EQ(report.outcome, CacheOutcome::kRebuilt);
  EXPECT_NE(report.detail.find("checksum"), std::string::npos) << report.detail;
  expectSameModel(a, b);
  cache.load(model_file_, 0.001f, params_, &report);
  EXPECT_EQ(report.outcome, CacheOutcome::kLoaded);  // the rebuilt entry replaced the bad one
}

TEST_F(ModelCacheTest, TruncatedStaleAndForeignEntriesAreRebuilt) {
  const ModelCache cache(dir_ / "cache");
  CacheReport report;
  cache.load(model_file_, 0.001f, params_, &report);
  const auto entry = report.entry;

  std::filesystem::resize_file(entry, std::filesystem::file_size(entry) - 10);
  cache.load(model_file_, 0.001f, params_, &report);
  EXPECT_EQ(report.outcome, CacheOutcome::kRebuilt);
  EXPECT_NE(report.detail.find("truncated"), std::string::npos) << report.detail;

  corrupt(entry, 8);  // format version field
  cache.load(model_file_, 0.001f, params_, &report);
  EXPECT_EQ(report.outcome, CacheOutcome::kRebuilt);
  EXPECT_NE(report.detail.find("version"), std::string::npos) << report.detail;

  std::ofstream(entry, std::ios::trunc)
      << "not a cache file at all, but long enough to hold a header";
  cache.load(model_file_, 0.001f, params_, &report);
  EXPECT_EQ(report.outcome, CacheOutcome::kRebuilt);
  EXPECT_NE(report.detail.find("not a stocs cache file"), std::string::npos) << report.detail;
}

// Regression: a corrupt payload size in the header allocated that many bytes (up to 16 GB)
// before the short file was noticed.
TEST_F(ModelCacheTest, AnnouncedPayloadLargerThanTheFileIsTruncation) {
  const ModelCache cache(dir_ / "cache");
  CacheReport report;
  cache.load(model_file_, 0.001f, params_, &report);
  {
    std::fstream f(report.entry, std::ios::in | std::ios::out | std::ios::binary);
    const uint64_t huge = uint64_t{1} << 33;
    f.seekp(24);  // payload_size: after magic, version, reserved and key
    f.write(reinterpret_cast<const char*>(&huge), sizeof huge);
  }
  cache.load(model_file_, 0.001f, params_, &report);
  EXPECT_EQ(report.outcome, CacheOutcome::kRebuilt);
  EXPECT_NE(report.detail.find("payload is truncated (8589934592 bytes announced"),
            std::string::npos)
      << report.detail;
}

TEST_F(ModelCacheTest, AnUnwritableFolderStillGivesTheModel) {
  std::ofstream(dir_ / "blocker") << "a file where the cache folder should be";
  const ModelCache cache(dir_ / "blocker" / "cache");
  CacheReport report;
  const PreparedModel m = cache.load(model_file_, 0.001f, params_, &report);
  EXPECT_EQ(report.outcome, CacheOutcome::kUncached);
  EXPECT_FALSE(report.detail.empty());
  EXPECT_GT(m.model.size(), 0u);
}

TEST_F(ModelCacheTest, DisabledCacheWritesNothingAndBadModelsStillThrow) {
  const ModelCache cache{std::filesystem::path()};
  CacheReport report;
  cache.load(model_file_, 0.001f, params_, &report);
  EXPECT_EQ(report.outcome, CacheOutcome::kUncached);
  EXPECT_THROW(cache.load((dir_ / "missing.ply").string(), 0.001f, params_), InputError);
  const ModelCache real(dir_ / "cache");
  EXPECT_THROW(real.load((dir_ / "missing.ply").string(), 0.001f, params_), InputError);
}

TEST(ModelCacheDefault, FollowsXdgCacheHome) {
  setenv("XDG_CACHE_HOME", "/tmp/stocs-xdg-test", 1);
  EXPECT_EQ(ModelCache::defaultDirectory(), std::filesystem::path("/tmp/stocs-xdg-test/stocs_ros"));
  unsetenv("XDG_CACHE_HOME");
  EXPECT_NE(ModelCache::defaultDirectory().string().find("stocs_ros"), std::string::npos);
}

}  // namespace
}  // namespace stocs
