// Congruent-set extraction on a known transform: the true correspondence is found, every set is
// congruent within the tolerance, sets are distinct and capped.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <set>

#include "stocs/estimation/stages/congruent_set_matcher.h"
#include "stocs/geometry/rigid_fit.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

class CongruentSetTest : public ::testing::Test {
 protected:
  void SetUp() override {
    model_.model = prepareModel(asymmetricMesh(), ModelSamplingParams{});
    model_.ppf_map = PpfHashMap::build(model_.model, PpfParams{});
    pose_ = test::viewingPose(0.6f);
  }

  /// Four well-spread model samples whose pair lines cross: the truth for the scene base.
  std::array<uint16_t, 4> chooseBase() const {
    const auto& p = model_.model.points;
    // Extremes along x and y of the model give a wide, well-conditioned quadrilateral.
    std::array<uint16_t, 4> idx{0, 0, 0, 0};
    for (size_t i = 0; i < p.size(); ++i) {
      if (p[i].x() < p[idx[0]].x()) idx[0] = static_cast<uint16_t>(i);
      if (p[i].x() > p[idx[1]].x()) idx[1] = static_cast<uint16_t>(i);
      if (p[i].y() < p[idx[2]].y()) idx[2] = static_cast<uint16_t>(i);
      if (p[i].y() > p[idx[3]].y()) idx[3] = static_cast<uint16_t>(i);
    }
    return idx;
  }

  /// The scene base: the model samples `idx` seen at pose_ (points, normals).
  void sceneBase(const std::array<uint16_t, 4>& idx, std::array<Eigen::Vector3f, 4>& points,
                 std::array<Eigen::Vector3f, 4>& normals) const {
    for (int k = 0; k < 4; ++k) {
      points[k] = pose_ * model_.model.points[idx[k]];
      normals[k] = pose_.linear() * model_.model.normals[idx[k]];
    }
  }

  PreparedModel model_;
  Eigen::Isometry3f pose_;
};

TEST_F(CongruentSetTest, TheTrueSetIsFoundAndEverySetIsCongruent) {
  const std::array<uint16_t, 4> truth = chooseBase();
  std::array<Eigen::Vector3f, 4> bp, bn;
  sceneBase(truth, bp, bn);
  CongruentSetParams params;
  params.max_sets = 100000;
  const CongruentSetMatcher matcher(model_, params);
  Rng rng(2);
  std::vector<CongruentSet> sets;
  ASSERT_GT(matcher.find(bp, bn, rng, sets), 0u);

  bool found_truth = false;
  std::set<CongruentSet> distinct;
  const auto& mp = model_.model.points;
  for (const CongruentSet& s : sets) {
    EXPECT_TRUE(distinct.insert(s).second) << "duplicate set";
    found_truth = found_truth || s == truth;
    for (int x = 0; x < 4; ++x) {
      for (int y = x + 1; y < 4; ++y) {
        ASSERT_NE(s[x], s[y]);
        EXPECT_LE(std::abs((mp[s[x]] - mp[s[y]]).norm() - (bp[x] - bp[y]).norm()),
                  params.tolerance + 1e-6f);
      }
    }
  }
  ASSERT_TRUE(found_truth);
  const auto fit = fitRigid({mp[truth[0]], mp[truth[1]], mp[truth[2]], mp[truth[3]]}, bp, 1e-4f);
  ASSERT_TRUE(fit);
  EXPECT_TRUE(fit->matrix().isApprox(pose_.matrix(), 1e-4f));
}

TEST_F(CongruentSetTest, SetsAreCappedWithoutDuplicates) {
  const std::array<uint16_t, 4> truth = chooseBase();
  std::array<Eigen::Vector3f, 4> bp, bn;
  sceneBase(truth, bp, bn);
  CongruentSetParams wide;
  wide.tolerance = 0.03f;  // loose enough to produce many sets
  wide.max_sets = 100000;
  Rng rng(3);
  std::vector<CongruentSet> all;
  const size_t total = CongruentSetMatcher(model_, wide).find(bp, bn, rng, all);
  ASSERT_GT(total, 20u);
  CongruentSetParams capped = wide;
  capped.max_sets = 7;
  std::vector<CongruentSet> some;
  EXPECT_EQ(CongruentSetMatcher(model_, capped).find(bp, bn, rng, some), 7u);
  ASSERT_EQ(some.size(), 7u);
  const std::set<CongruentSet> distinct(some.begin(), some.end());
  EXPECT_EQ(distinct.size(), 7u);
  for (const CongruentSet& s : some) EXPECT_NE(std::find(all.begin(), all.end(), s), all.end());
}

TEST_F(CongruentSetTest, ABaseWithParallelPairLinesIsSkipped) {
  // Collinear base: no split has crossing lines.
  std::array<Eigen::Vector3f, 4> bp = {Eigen::Vector3f(0, 0, 0.6f), Eigen::Vector3f(0.02f, 0, 0.6f),
                                       Eigen::Vector3f(0.05f, 0, 0.6f),
                                       Eigen::Vector3f(0.09f, 0, 0.6f)};
  std::array<Eigen::Vector3f, 4> bn;
  bn.fill(Eigen::Vector3f(0, 0, -1));
  Rng rng(1);
  std::vector<CongruentSet> sets;
  EXPECT_EQ(CongruentSetMatcher(model_, CongruentSetParams{}).find(bp, bn, rng, sets), 0u);
  EXPECT_TRUE(sets.empty());
}

}  // namespace
}  // namespace stocs
