// The adaptive stop of the base loop: when the best bases all agree on the best one's place.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "stocs/estimation/scheduling/base_consensus.h"
#include "stocs/model/object_model.h"
#include "test_support.h"

namespace stocs {
namespace {

class BaseConsensusTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // A 10 x 6 x 4 cm box: turned 180 degrees about z it shows the same surface.
    box_ = prepareModel(boxMesh({0.1f, 0.06f, 0.04f}), ModelSamplingParams{});
    here_ = test::viewingPose(0.6f);
    turned_ = here_;
    turned_.rotate(Eigen::AngleAxisf(static_cast<float>(M_PI), Eigen::Vector3f::UnitZ()));
    nudged_ = here_;
    nudged_.translate(Eigen::Vector3f(0.003f, 0, 0));
    beside_ = here_;
    beside_.translate(Eigen::Vector3f(0.1f, 0, 0));
  }

  BaseConsensus consensus(int needed) const {
    return BaseConsensus(box_, 0.1f * box_.diameter, needed);
  }

  ObjectModel box_;
  Eigen::Isometry3f here_, turned_, nudged_, beside_;
};

TEST_F(BaseConsensusTest, ReachedWhenTheBestAllAgreeUpToSymmetry) {
  BaseConsensus c = consensus(3);
  c.add(0, 10, here_);
  EXPECT_FALSE(c.reached());  // too few bases yet
  c.add(1, 9, turned_);       // the box's symmetry: the same place
  EXPECT_FALSE(c.reached());
  c.add(2, 8, nudged_);
  EXPECT_TRUE(c.reached());
}

TEST_F(BaseConsensusTest, ADisagreeingBaseAmongTheBestPreventsItUntilPushedOut) {
  BaseConsensus c = consensus(3);
  c.add(0, 10, here_);
  c.add(1, 9, beside_);
  c.add(2, 8, nudged_);
  EXPECT_FALSE(c.reached());
  c.add(3, 1, turned_);  // agrees, but ranks below the three best
  EXPECT_FALSE(c.reached());
  c.add(4, 9.5f, turned_);  // the three best are now here, turned, beside
  EXPECT_FALSE(c.reached());
  c.add(5, 9.6f, nudged_);  // and now here, nudged, turned
  EXPECT_TRUE(c.reached());
}

TEST_F(BaseConsensusTest, ANewBestIsJudgedAfresh) {
  BaseConsensus c = consensus(2);
  c.add(0, 5, here_);
  c.add(1, 4, nudged_);
  EXPECT_TRUE(c.reached());
  c.add(2, 6, beside_);  // a better base elsewhere: the second best no longer agrees with the best
  EXPECT_FALSE(c.reached());
  c.add(3, 5.5f, beside_);
  EXPECT_TRUE(c.reached());
}

TEST_F(BaseConsensusTest, EqualScoresRankByBaseIndexAndEmptyBasesAreIgnored) {
  BaseConsensus c = consensus(2);
  c.add(5, 5, beside_);
  c.add(2, 5, here_);  // the same score at a lower index: the best, ahead of base 5
  c.add(8, 0, here_);
  c.add(9, -1, here_);
  EXPECT_FALSE(c.reached());
  c.add(7, 5, nudged_);  // the same score again, but after base 5
  EXPECT_FALSE(c.reached());
  c.add(4, 5, nudged_);  // before base 5: the two best are bases 2 and 4
  EXPECT_TRUE(c.reached());
}

TEST_F(BaseConsensusTest, TheCallersTestOfTheBestPoseMustPassToo) {
  std::vector<int> asked;
  // Base 0's pose fails the test (the estimator's: in free space once refined).
  BaseConsensus c(box_, 0.1f * box_.diameter, 2, [&](int base) {
    asked.push_back(base);
    return base != 0;
  });
  c.add(0, 5, here_);
  c.add(1, 4, nudged_);
  EXPECT_FALSE(c.reached());  // they agree, on a pose the test rejects
  EXPECT_FALSE(c.reached());
  c.add(2, 3, turned_);  // not a new best: the answer stands without asking again
  EXPECT_FALSE(c.reached());
  c.add(3, 6, turned_);  // a new best, asked once
  EXPECT_TRUE(c.reached());
  EXPECT_TRUE(c.reached());
  EXPECT_EQ(asked, (std::vector<int>{0, 3}));
}

}  // namespace
}  // namespace stocs
