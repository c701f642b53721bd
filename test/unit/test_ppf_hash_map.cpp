// The model PPF map: voting (every model pair is found), lookups, and serialisation.
#include <gtest/gtest.h>

#include <cstring>

#include <map>
#include <set>
#include <sstream>

#include "stocs/model/ppf_hash_map.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

class PpfHashMapTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ModelSamplingParams sampling;
    sampling.sampling_ratio = 0.08f;
    model_ = prepareModel(boxMesh({0.1f, 0.06f, 0.04f}), sampling);
    map_ = PpfHashMap::build(model_, params_);
  }
  PpfParams params_;
  ObjectModel model_;
  PpfHashMap map_;
};

TEST_F(PpfHashMapTest, StoresEachPairAboveTheMinimumDistanceOnce) {
  size_t expected = 0;
  const float min_d = params_.min_distance_ratio * model_.diameter;
  for (size_t i = 0; i < model_.size(); ++i) {
    for (size_t j = i + 1; j < model_.size(); ++j)
      expected += (model_.points[i] - model_.points[j]).norm() >= min_d;
  }
  EXPECT_EQ(map_.pairCount(), expected);
  EXPECT_GT(map_.occupiedKeyCount(), 10u);
  EXPECT_LT(map_.memoryBytes(), 2u << 20);
}

TEST_F(PpfHashMapTest, EveryModelPairIsConsistentAndFindsItselfInBothOrders) {
  const auto& p = model_.points;
  const auto& n = model_.normals;
  const float min_d = params_.min_distance_ratio * model_.diameter;
  int checked = 0;
  for (size_t i = 0; i < p.size(); i += 3) {
    for (size_t j = 0; j < p.size(); j += 5) {
      if (i == j || (p[i] - p[j]).norm() < min_d) continue;
      ASSERT_TRUE(map_.consistent(p[i], n[i], p[j], n[j]));
      bool found = false;
      std::set<std::pair<int, int>> seen;
      map_.forEachMatch(p[i], n[i], p[j], n[j], [&](uint16_t a, uint16_t b) {
        EXPECT_TRUE(seen.emplace(a, b).second) << "ordered pair reported twice";
        found = found || (a == i && b == j);
      });
      ASSERT_TRUE(found) << "pair (" << i << ", " << j << ") not among its own matches";
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
}

TEST_F(PpfHashMapTest, MatchesAgreeWithTheQueryFeatureWithinTheBinTolerance) {
  const auto& p = model_.points;
  const auto& n = model_.normals;
  const size_t i = 0, j = p.size() / 2;
  const PpfFeature q = computePpf(p[i], n[i], p[j], n[j]);
  const float step = params_.angle_step_deg * static_cast<float>(M_PI) / 180;
  int matches = 0;
  map_.forEachMatch(p[i], n[i], p[j], n[j], [&](uint16_t a, uint16_t b) {
    const PpfFeature f = computePpf(p[a], n[a], p[b], n[b]);
    EXPECT_LT(std::abs(f.distance - q.distance), 2 * params_.distance_step);
    EXPECT_LT(std::abs(f.angle_n1_d - q.angle_n1_d), 2 * step);
    EXPECT_LT(std::abs(f.angle_n2_d - q.angle_n2_d), 2 * step);
    EXPECT_LT(std::abs(f.angle_n1_n2 - q.angle_n1_n2), 2 * step);
    ++matches;
  });
  EXPECT_GT(matches, 0);
}

TEST_F(PpfHashMapTest, FeaturesAbsentFromTheModelAreInconsistent) {
  // Longer than the object: never on the model.
  EXPECT_FALSE(map_.consistent({0, 0, 0}, {0, 0, 1}, {0.5f, 0, 0}, {0, 0, 1}));
  // Shorter than the minimum stored distance.
  EXPECT_FALSE(map_.consistent({0, 0, 0}, {0, 0, 1}, {0.001f, 0, 0}, {0, 0, 1}));
  // A box has only parallel or perpendicular normals: two normals at 45 degrees, both at 45 degrees
  // to the connecting line, never occur.
  const Eigen::Vector3f n1 = Eigen::Vector3f(1, 0, 1).normalized(),
                        n2 = Eigen::Vector3f(1, 1, 0).normalized();
  EXPECT_FALSE(map_.consistent({0, 0, 0}, n1, {0.05f, 0, 0}, n2));
}

TEST_F(PpfHashMapTest, SerialisationRoundTripsExactly) {
  std::stringstream buffer;
  map_.write(buffer);
  const PpfHashMap copy = PpfHashMap::read(buffer, model_.size());
  EXPECT_EQ(copy.pairCount(), map_.pairCount());
  EXPECT_EQ(copy.occupiedKeyCount(), map_.occupiedKeyCount());
  EXPECT_EQ(copy.memoryBytes(), map_.memoryBytes());
  const auto& p = model_.points;
  const auto& n = model_.normals;
  for (size_t i = 0; i < p.size(); i += 7) {
    for (size_t j = 1; j < p.size(); j += 11) {
      std::vector<std::pair<int, int>> a, b;
      map_.forEachMatch(p[i], n[i], p[j], n[j],
                        [&](uint16_t x, uint16_t y) { a.emplace_back(x, y); });
      copy.forEachMatch(p[i], n[i], p[j], n[j],
                        [&](uint16_t x, uint16_t y) { b.emplace_back(x, y); });
      ASSERT_EQ(a, b);
    }
  }
}

TEST_F(PpfHashMapTest, ReadRejectsTruncatedOrInconsistentData) {
  std::stringstream buffer;
  map_.write(buffer);
  const std::string bytes = buffer.str();
  std::istringstream truncated(bytes.substr(0, bytes.size() / 2));
  EXPECT_THROW(PpfHashMap::read(truncated, model_.size()), InputError);
  std::istringstream too_few_samples(bytes);
  EXPECT_THROW(PpfHashMap::read(too_few_samples, 3), InputError);  // pair indices out of range
  std::string bad = bytes;
  bad[0] = bad[1] = bad[2] = bad[3] = '\xff';  // distance step becomes NaN
  std::istringstream bad_header(bad);
  EXPECT_THROW(PpfHashMap::read(bad_header, model_.size()), InputError);
}

/// What PpfHashMap::read says about `bytes`, or "" when it accepts them.
std::string readError(const std::string& bytes, size_t model_size) {
  std::istringstream in(bytes);
  try {
    PpfHashMap::read(in, model_size);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Regression (fuzz_ppf_map): a corrupt pair count allocated up to 8 GB before the short stream
// was noticed.
TEST_F(PpfHashMapTest, CorruptCountsFailWithoutAllocatingWhatTheyClaim) {
  std::stringstream buffer;
  map_.write(buffer);
  std::string bytes = buffer.str();
  const auto count_at = [&](size_t offset) {
    uint64_t n = 0;
    std::memcpy(&n, bytes.data() + offset, sizeof n);
    return n;
  };
  const size_t keys_at = 4 * sizeof(float);
  const size_t offsets_at = keys_at + 8 + 4 * count_at(keys_at);
  const size_t pairs_at = offsets_at + 8 + 4 * count_at(offsets_at);
  const uint64_t claimed = uint64_t{2'000'000'000};
  bytes.replace(pairs_at, 8, reinterpret_cast<const char*>(&claimed), 8);
  EXPECT_EQ(readError(bytes, model_.size()), "PPF map is truncated");
}

// Regression (found while fuzzing PpfHashMap::read): fine steps over a long range made the key
// count wrap in 32 bits, so lookups indexed past the occupancy bits.
TEST_F(PpfHashMapTest, MoreBinsThan32BitKeysAreRejected) {
  std::stringstream buffer;
  map_.write(buffer);
  std::string bytes = buffer.str();
  const float fine[4] = {1e-4f, 0.011f, 0.0f, 19.0f};  // distance step, angle step, min, max
  bytes.replace(0, sizeof fine, reinterpret_cast<const char*>(fine), sizeof fine);
  EXPECT_EQ(readError(bytes, model_.size()), "PPF map header gives too many bins");
  PpfParams fine_params;
  fine_params.distance_step = 1e-4f;
  fine_params.angle_step_deg = 1.0f;
  ObjectModel huge = model_;
  huge.diameter = 10.0f;
  EXPECT_THROW(PpfHashMap::build(huge, fine_params), InputError);
}

}  // namespace
}  // namespace stocs
